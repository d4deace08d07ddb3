// Writes tests/files/scene.babylon: Babylon.js's own SceneSerializer.Serialize(scene) (the pinned
// @babylonjs/core package, in node with a NullEngine) of a scene with one directional light, a
// CascadedShadowGenerator (4 cascades of 2048, lambda 0.7) and a FreeCamera (minZ 0.5, maxZ 800,
// fov 0.8 rad) looking along +z with the sun behind it, up and to the camera's right.
//
// usage: node babylon_scene.mjs PACKAGE_ROOT   (prints the file's text on stdout)
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root] = process.argv.slice(2);
const B = await import(pathToFileURL(path.join(root, "node_modules", "@babylonjs", "core", "index.js")).href);
B.Logger.LogLevels = B.Logger.NoneLogLevel; // stdout carries the JSON only
B.RenderTargetTexture.prototype.createDepthStencilTexture = function () {};

const engine = new B.NullEngine({ renderWidth: 1920, renderHeight: 1080 });
engine._features.supportCSM = true;
engine._features.supportShadowSamplers = true; // WebGL2 and WebGPU: the generator picks PCF, as in a browser
const scene = new B.Scene(engine);
const camera = new B.FreeCamera("camera", new B.Vector3(0, 2, 0), scene);
camera.setTarget(new B.Vector3(0, 2, 10));
camera.minZ = 0.5;
camera.maxZ = 800;
camera.fov = 0.8;
scene.activeCamera = camera;
// towards the light: up, behind the camera (-z) and to its right (+x in Babylon's left-handed frame)
const light = new B.DirectionalLight("sun", new B.Vector3(-1, -2, 1).normalize(), scene);
const csm = new B.CascadedShadowGenerator(2048, light);
csm.numCascades = 4;
csm.lambda = 0.7;
const ground = B.MeshBuilder.CreateGround("ground", { width: 100, height: 100 }, scene);
csm.addShadowCaster(ground);
ground.geometry.id = "ground-geometry"; // a fixed id (a random one by default): the same file on every run
process.stdout.write(JSON.stringify(B.SceneSerializer.Serialize(scene), null, 2) + "\n");
