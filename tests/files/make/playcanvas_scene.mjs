// Reads tests/files/scene.playcanvas.json with PlayCanvas's own SceneParser (the pinned `playcanvas`
// package's ES modules, build/playcanvas/src, on a NullGraphicsDevice in node) and prints, as JSON,
// what the engine made of it: the directional light component's and the camera component's values
// for the keys the toolkit reads, the world direction towards the light (the light entity's up: it
// shines along its -Y) and the camera's forward (its -Z).
//
// usage: node playcanvas_scene.mjs PACKAGE_ROOT SCENE_JSON   (prints the JSON on stdout)
import { pathToFileURL } from "node:url";
import path from "node:path";
import fs from "node:fs";

const [root, file] = process.argv.slice(2);
const src = (p) => import(pathToFileURL(path.join(root, "node_modules", "playcanvas", "build", "playcanvas", "src", p)).href);
const { NullGraphicsDevice } = await src("platform/graphics/null/null-graphics-device.js");
const { AppBase } = await src("framework/app-base.js");
const { AppOptions } = await src("framework/app-options.js");
const { LightComponentSystem } = await src("framework/components/light/system.js");
const { CameraComponentSystem } = await src("framework/components/camera/system.js");
const { SceneParser } = await src("framework/parsers/scene.js");

const device = new NullGraphicsDevice({ width: 1920, height: 1080 });
device.maxTextureSize = 16384;
const app = new AppBase({ id: "canvas", width: 1920, height: 1080, getBoundingClientRect: () => ({ width: 1920, height: 1080 }) });
const options = new AppOptions();
options.graphicsDevice = device;
options.componentSystems = [LightComponentSystem, CameraComponentSystem];
app.init(options);
const data = JSON.parse(fs.readFileSync(file, "utf8"));
const top = new SceneParser(app, false).parse(data);
const all = [];
const walk = (e) => { all.push(e); e.children.forEach(walk); };
walk(top);
const sun = all.find((e) => e.light && e.light.type === "directional");
const cam = all.find((e) => e.camera);
const keys = ["castShadows", "numCascades", "cascadeDistribution", "cascadeBlend", "shadowDistance", "shadowResolution", "shadowBias",
  "normalOffsetBias", "shadowType", "vsmBlurSize", "vsmBlurMode", "vsmBias"];
const out = {
  light: Object.fromEntries(keys.map((k) => [k, sun.light[k]])),
  camera: { fov: cam.camera.fov, horizontalFov: cam.camera.horizontalFov, nearClip: cam.camera.nearClip, farClip: cam.camera.farClip },
  towards_light: [sun.up.x, sun.up.y, sun.up.z],
  camera_forward: [cam.forward.x, cam.forward.y, cam.forward.z],
};
process.stdout.write(JSON.stringify(out, null, 2) + "\n");
