// Runs three.js's own CSM classes (examples/jsm/csm/CSM.js and CSMFrustum.js from the pinned
// `three` package) in node with a PerspectiveCamera and prints the cascades as JSON on stdout
// (tests/test_engines_js.py reads it).
//
// usage: node three_csm.mjs PACKAGE_ROOT JSON
//   PACKAGE_ROOT  the directory holding node_modules/three (the test's checked cache)
//   JSON          {"lights": [[x, y, z], ...], "cases": [{"near", "far", "max_far", "fov", "aspect", "k", "map_size"}, ...]}
//                 far: the camera's far plane, max_far: CSM's maxFar (shadows end at the smaller);
//                 fov: the vertical full angle [deg]; k: null for CSM's default; lights: towards the
//                 light, in the toolkit's eye frame (x right, y up, z along the view).
// three.js's matrices and vectors are float64 (plain JavaScript numbers).
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root, text] = process.argv.slice(2);
const args = JSON.parse(text);
const load = (p) => import(pathToFileURL(path.join(root, "node_modules", "three", p)).href);
const THREE = await load("build/three.module.js");
const { CSM } = await load("examples/jsm/csm/CSM.js");

const eyeFromView = (v) => [v.x, v.y, -v.z]; // three's view space looks along -z; the toolkit's along +z

function run(c) {
  const camera = new THREE.PerspectiveCamera(c.fov, c.aspect, c.near, c.far);
  camera.rotation.set(Math.PI / 2, 0, 0); // three's view direction -z turns to world +y
  camera.updateMatrixWorld(true);
  const parent = new THREE.Object3D(); // stands in for the scene: CSM adds its lights to it
  const rows = [];
  for (const l of args.lights) {
    const shine = new THREE.Vector3(-l[0], -l[1], l[2]).transformDirection(camera.matrixWorld); // along -L, in world
    const data = { camera, parent, maxFar: c.max_far, shadowMapSize: c.map_size, lightDirection: shine };
    if (c.k !== null) data.cascades = c.k;
    const csm = new CSM(data);
    csm.update();
    rows.push({
      k: csm.cascades,
      breaks: [...csm.breaks],
      cascades: csm.frustums.map((f, i) => {
        const shadow = csm.lights[i].shadow.camera;
        return {
          end: -f.vertices.far[0].z,
          corners: [...f.vertices.near, ...f.vertices.far].map(eyeFromView),
          side_x: shadow.right - shadow.left,
          side_y: shadow.top - shadow.bottom,
        };
      }),
    });
    csm.remove();
  }
  return { rows };
}

process.stdout.write(JSON.stringify({ engine: "three", revision: THREE.REVISION, float64: true, cases: args.cases.map(run) }) + "\n");
