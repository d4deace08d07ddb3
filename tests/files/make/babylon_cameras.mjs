// Writes tests/files/babylon_cameras.json: Babylon.js's own serialize() of an ArcRotateCamera (alpha 0.3,
// beta 1.1, radius 10, target (1, 2, 3)) and of a FreeCamera (rotation pitch 0.4, yaw 0.7), each with the
// engine's own forward direction (camera.getDirection(Vector3.Forward())), for the reader's camera forward.
//
// usage: node babylon_cameras.mjs PACKAGE_ROOT   (prints the JSON on stdout)
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root] = process.argv.slice(2);
const B = await import(pathToFileURL(path.join(root, "node_modules", "@babylonjs", "core", "index.js")).href);
B.Logger.LogLevels = B.Logger.NoneLogLevel; // stdout carries the JSON only
const engine = new B.NullEngine();
const scene = new B.Scene(engine);
const arc = new B.ArcRotateCamera("arc", 0.3, 1.1, 10, new B.Vector3(1, 2, 3), scene);
const free = new B.FreeCamera("free", new B.Vector3(0, 0, 0), scene);
free.rotation = new B.Vector3(0.4, 0.7, 0);
const out = [];
for (const c of [arc, free]) {
  c.computeWorldMatrix(true);
  c.getViewMatrix(true);
  const d = c.getDirection(B.Vector3.Forward());
  const json = c.serialize();
  delete json.inputsmgr; // the input managers' key maps: not the camera's pose
  out.push({ camera: json, forward: [d.x, d.y, d.z] });
}
process.stdout.write(JSON.stringify(out, null, 1) + "\n");
