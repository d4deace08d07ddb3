// Runs Babylon.js's own CascadedShadowGenerator (from the pinned @babylonjs/core package) in node with a
// NullEngine, in the engine's default float32 matrices, set up as the frames' page sets it up
// (aliasing/frames/pages/babylon.mjs: a FreeCamera at the job's eye with its up, setTarget, fov, minZ,
// maxZ; a DirectionalLight along -sun; the casters' float32 positions, z negated), and prints each
// cascade's transform matrix (row vectors, Babylon's world), per job, as one JSON list on stdout
// (tests/test_frames.py).
//
// usage: node babylon_csm_float32.mjs PACKAGE_ROOT JOB_FILE...
//   PACKAGE_ROOT  the directory holding node_modules/@babylonjs/core (aliasing.frames.install.package_root)
//   JOB_FILE      the page's job (aliasing.frames.run.make_job) as JSON
import { pathToFileURL } from "node:url";
import path from "node:path";
import fs from "node:fs";

const [root, ...jobFiles] = process.argv.slice(2);
// the modules the page imports (not the whole package: node loads them in a fraction of the time)
const core = (m) => import(pathToFileURL(path.join(root, "node_modules", "@babylonjs", "core", m)).href);
const B = {};
for (const m of ["Engines/nullEngine.js", "scene.js", "Cameras/freeCamera.js", "Lights/directionalLight.js", "Lights/Shadows/cascadedShadowGenerator.js",
  "Lights/Shadows/shadowGeneratorSceneComponent.js", "Meshes/mesh.js", "Meshes/mesh.vertexData.js", "Materials/Textures/renderTargetTexture.js",
  "Maths/math.vector.js", "Engines/engine.js", "Misc/logger.js"]) Object.assign(B, await core(m));
B.Logger.LogLevels = B.Logger.NoneLogLevel; // stdout carries the JSON only
B.RenderTargetTexture.prototype.createDepthStencilTexture = function () {}; // no WebGL: the matrices never read it

function run(job) {
  const engine = new B.NullEngine({ renderWidth: job.width, renderHeight: job.height });
  engine._features.supportCSM = true; // the NullEngine reports no CSM support; the cascades are arithmetic
  const scene = new B.Scene(engine);
  const c = job.camera, s = job.settings;
  const mz = (v) => new B.Vector3(v[0], v[1], -v[2]);
  const camera = new B.FreeCamera("camera", mz(c.eye), scene);
  camera.upVector = mz(c.up);
  camera.setTarget(mz(c.target));
  camera.fov = c.fov * Math.PI / 180;
  camera.minZ = c.near; camera.maxZ = c.far;
  scene.activeCamera = camera;
  const light = new B.DirectionalLight("sun", mz([-job.sun[0], -job.sun[1], -job.sun[2]]), scene);
  const csm = new B.CascadedShadowGenerator(s.mapSize ?? 1024, light);
  for (const k of ["numCascades", "lambda", "stabilizeCascades", "depthClamp", "shadowMaxZ"]) if (s[k] !== undefined && s[k] !== null) csm[k] = s[k];
  const raw = Buffer.from(job.triangles, "base64");
  const pos = new Float32Array(raw.buffer.slice(raw.byteOffset, raw.byteOffset + raw.length));
  for (let i = 2; i < pos.length; i += 3) pos[i] = -pos[i];
  const mesh = new B.Mesh("scene", scene);
  const vd = new B.VertexData();
  vd.positions = Array.from(pos);
  vd.indices = Array.from({ length: pos.length / 3 }, (_, i) => i);
  vd.applyToMesh(mesh);
  csm.addShadowCaster(mesh);
  camera.getViewMatrix(true); // computed now, as scene.render does first: the lazy first use leaves them NaN
  camera.getProjectionMatrix(true);
  mesh.computeWorldMatrix(true);
  csm._computeShadowCastersBoundingInfo();
  csm._splitFrustum();
  csm._computeMatrices();
  const matrices = [];
  for (let i = 0; i < csm.numCascades; i++) matrices.push(Array.from(csm.getCascadeTransformMatrix(i).m));
  const float32 = camera.getViewMatrix().m instanceof Float32Array;
  scene.dispose();
  engine.dispose();
  return { version: B.Engine.Version, float32, matrices };
}

process.stdout.write(JSON.stringify(jobFiles.map((f) => run(JSON.parse(fs.readFileSync(f, "utf8"))))) + "\n");
