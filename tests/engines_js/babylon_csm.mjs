// Runs Babylon.js's own CascadedShadowGenerator (from the pinned @babylonjs/core package) in node
// with a NullEngine and prints its cascades as JSON on stdout (tests/test_engines_js.py reads it).
//
// usage: node babylon_csm.mjs PACKAGE_ROOT JSON
//   PACKAGE_ROOT  the directory holding node_modules/@babylonjs/core (the test's checked cache)
//   JSON          {"lights": [[x, y, z], ...], "cases": [{"near", "far", "fov", "width", "height", "k", "map_size"}, ...]}
//                 fov: the vertical full angle [deg] (Babylon's FOVMODE_VERTICAL_FIXED); aspect =
//                 width/height (the render size); k: null for the engine's default; lights: towards
//                 the light, in the toolkit's eye frame (x right, y up, z along the view).
// The camera sits at the origin looking along world +y: Babylon builds each cascade's light view
// from world up, which is then the view vector, as the toolkit's light space is (Wimmer 2004 §3.4).
// Matrices are float64 (useHighPrecisionMatrix).
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root, text] = process.argv.slice(2);
const args = JSON.parse(text);
const B = await import(pathToFileURL(path.join(root, "node_modules", "@babylonjs", "core", "index.js")).href);
B.Logger.LogLevels = B.Logger.NoneLogLevel; // stdout carries the JSON only
// float64 everywhere: the matrices the modules made at import (the generator's TmpMatrix among them) are
// converted only by the first SetMatrixPrecision call, and AbstractEngine's constructor makes that call
// without useHighPrecisionMatrix before the NullEngine's own: left alone, the light views stay Float32Array
// and the tight boxes agree with float64 to about 2e-8 only.
B.PerformanceConfigurator.SetMatrixPrecision(true);
// The shadow map's depth texture needs WebGL, which the NullEngine lacks; the cascade matrices never read it.
B.RenderTargetTexture.prototype.createDepthStencilTexture = function () {};

function run(c) {
  const engine = new B.NullEngine({ renderWidth: c.width, renderHeight: c.height, useHighPrecisionMatrix: true });
  engine._features.supportCSM = true; // the NullEngine reports no CSM support; the cascades are arithmetic
  const scene = new B.Scene(engine);
  const camera = new B.FreeCamera("eye", new B.Vector3(0, 0, 0), scene);
  camera.fov = (c.fov * Math.PI) / 180;
  camera.minZ = c.near;
  camera.maxZ = c.far;
  camera.rotation = new B.Vector3(-Math.PI / 2, 0, 0); // look along world +y
  scene.activeCamera = camera;
  camera.getProjectionMatrix(true); // computed now: the lazy first use left the transformation NaN
  const view = camera.getViewMatrix(true);
  const invView = B.Matrix.Invert(view);
  const toEye = (v) => B.Vector3.TransformCoordinates(v, view).asArray();
  // high precision: the matrices hold plain (float64) arrays, not Float32Array
  const result = { aspect: engine.getAspectRatio(camera), float64: Array.isArray(view.m) && Array.isArray(camera.getProjectionMatrix().m), stable: [], tight: [] };
  for (const stabilize of [true, false]) {
    for (const l of args.lights) {
      const dirWorld = B.Vector3.TransformNormal(new B.Vector3(-l[0], -l[1], -l[2]), invView); // it shines along -L
      const light = new B.DirectionalLight("sun", dirWorld, scene);
      const gen = new B.CascadedShadowGenerator(c.map_size, light, true, camera);
      if (c.k !== null) gen.numCascades = c.k;
      gen.stabilizeCascades = stabilize;
      gen._splitFrustum();
      gen._computeMatrices();
      const cascades = [];
      for (let i = 0; i < gen.numCascades; i++) {
        cascades.push({
          end: gen._viewSpaceFrustumsZ[i],
          corners: gen._frustumCornersWorldSpace[i].map(toEye),
          min: gen._cascadeMinExtents[i].asArray(),
          max: gen._cascadeMaxExtents[i].asArray(),
        });
      }
      (stabilize ? result.stable : result.tight).push({ k: gen.numCascades, cascades });
      gen.dispose();
      light.dispose();
    }
  }
  scene.dispose();
  engine.dispose();
  return result;
}

const G = B.CascadedShadowGenerator;
process.stdout.write(JSON.stringify({
  engine: "babylon",
  version: B.Engine.Version,
  counts: { default: G.DEFAULT_CASCADES_COUNT, min: G.MIN_CASCADES_COUNT, max: G.MAX_CASCADES_COUNT },
  cases: args.cases.map(run),
}) + "\n");
