// Writes tests/files/scene.three.json: three.js's own scene.toJSON() (the pinned `three` package, in
// node) of a scene with a PerspectiveCamera (fov 50° vertical, near 0.1, far 500, aspect 16:9) at
// (0, 2, 0) looking along -z, and a DirectionalLight casting a shadow (bias -0.0005, normalBias 0.02,
// a 2048² map, a ±30 box) placed up, behind and to the camera's right of its target at the origin.
//
// usage: node three_scene.mjs PACKAGE_ROOT   (prints the file's text on stdout)
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root] = process.argv.slice(2);
const THREE = await import(pathToFileURL(path.join(root, "node_modules", "three", "build", "three.module.js")).href);

const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(50, 16 / 9, 0.1, 500);
camera.name = "Camera";
camera.position.set(0, 2, 0);
camera.lookAt(0, 2, -10);
scene.add(camera);
const rig = new THREE.Group();
rig.name = "Rig";
rig.position.set(0, 1, 0);
scene.add(rig);
const light = new THREE.DirectionalLight(0xffffff, 3);
light.name = "Sun";
light.position.set(10, 19, 10); // world (10, 20, 10): up, behind (+z) and to the right (+x) of a camera looking along -z
light.castShadow = true;
light.shadow.bias = -0.0005;
light.shadow.normalBias = 0.02;
light.shadow.mapSize.set(2048, 2048);
Object.assign(light.shadow.camera, { left: -30, right: 30, top: 30, bottom: -30, near: 0.5, far: 100 });
light.shadow.camera.updateProjectionMatrix();
rig.add(light);
scene.add(light.target); // the target at the origin, in the file
scene.updateMatrixWorld(true);
let n = 0; // fixed uuids: the same file on every run
for (const o of [scene, camera, rig, light, light.target, light.shadow.camera]) o.uuid = `00000000-0000-4000-8000-${String(++n).padStart(12, "0")}`;
process.stdout.write(JSON.stringify(scene.toJSON(), null, "\t") + "\n");
