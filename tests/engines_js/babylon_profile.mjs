// Runs Babylon.js's own CascadedShadowGenerator and ShadowGenerator (from the pinned @babylonjs/core
// package) in node with a NullEngine for the toolkit's Babylon.js profile (aliasing/setups/babylon.py)
// and prints, as JSON on stdout:
//   defaults: the engine's own default objects' values for the profile's setting keys (a new
//             CascadedShadowGenerator, a new ShadowGenerator, their DirectionalLight, a new
//             StandardMaterial) and what the setters make of out-of-range values;
//   cases:    per case and light direction, each cascade's texel (its light-space box's x and y
//             extents ÷ mapSize) and its box's extent along the light.
//
// usage: node babylon_profile.mjs PACKAGE_ROOT JSON
//   JSON {"lights": [[x, y, z], ...] (towards the light, toolkit eye frame), "cases": [{"near", "far",
//         "fov" (vertical, deg), "width", "height" (render size: aspect = width/height),
//         "settings": {profile keys: values}}, ...]}
// The engine is a WebGL2-like NullEngine: CSM support and shadow samplers on (the generator then
// picks PCF, as in a browser), float64 matrices (see babylon_csm.mjs).
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root, text] = process.argv.slice(2);
const args = JSON.parse(text);
const B = await import(pathToFileURL(path.join(root, "node_modules", "@babylonjs", "core", "index.js")).href);
B.Logger.LogLevels = B.Logger.NoneLogLevel; // stdout carries the JSON only
B.PerformanceConfigurator.SetMatrixPrecision(true);
B.RenderTargetTexture.prototype.createDepthStencilTexture = function () {};

function makeScene(c) {
  const engine = new B.NullEngine({ renderWidth: c.width, renderHeight: c.height, useHighPrecisionMatrix: true });
  engine._features.supportCSM = true;
  engine._features.supportShadowSamplers = true; // WebGL2 and WebGPU have comparison samplers
  const scene = new B.Scene(engine);
  const camera = new B.FreeCamera("eye", new B.Vector3(0, 0, 0), scene);
  camera.fov = (c.fov * Math.PI) / 180;
  camera.minZ = c.near;
  camera.maxZ = c.far;
  camera.rotation = new B.Vector3(-Math.PI / 2, 0, 0); // look along world +y
  scene.activeCamera = camera;
  camera.getProjectionMatrix(true);
  return { engine, scene, camera };
}

const filterNames = ["FILTER_NONE", "FILTER_EXPONENTIALSHADOWMAP", "FILTER_POISSONSAMPLING", "FILTER_BLUREXPONENTIALSHADOWMAP",
  "FILTER_CLOSEEXPONENTIALSHADOWMAP", "FILTER_BLURCLOSEEXPONENTIALSHADOWMAP", "FILTER_PCF", "FILTER_PCSS"];
const qualityNames = ["QUALITY_HIGH", "QUALITY_MEDIUM", "QUALITY_LOW"];

function defaults() {
  const { engine, scene, camera } = makeScene({ width: 1920, height: 1080, fov: 50, near: 0.1, far: 500 });
  const light = new B.DirectionalLight("sun", new B.Vector3(0.3, -1, 0.2), scene);
  const gen = new B.CascadedShadowGenerator(1024, light, undefined, camera);
  const plain = new B.ShadowGenerator(1024, new B.DirectionalLight("sun2", new B.Vector3(0.3, -1, 0.2), scene));
  const material = new B.StandardMaterial("m", scene);
  const values = {
    numCascades: gen.numCascades, lambda: gen.lambda, cascadeBlendPercentage: gen.cascadeBlendPercentage,
    stabilizeCascades: gen.stabilizeCascades, shadowMaxZ: gen.shadowMaxZ, minDistance: gen.minDistance, maxDistance: gen.maxDistance,
    depthClamp: gen.depthClamp, autoCalcDepthBounds: gen.autoCalcDepthBounds, bias: gen.bias, normalBias: gen.normalBias,
    filter: filterNames[gen.filter], filteringQuality: qualityNames[gen.filteringQuality],
    contactHardeningLightSizeUVRatio: gen.contactHardeningLightSizeUVRatio, frustumEdgeFalloff: gen.frustumEdgeFalloff,
    forceBackFacesOnly: gen.forceBackFacesOnly, darkness: gen.darkness, depthScale: gen.depthScale, useKernelBlur: gen.useKernelBlur,
    blurKernel: gen.blurKernel, blurBoxOffset: gen.blurBoxOffset, blurScale: gen.blurScale, "material.backFaceCulling": material.backFaceCulling,
    "material.cullBackFaces": material.cullBackFaces, "light.shadowFrustumSize": light.shadowFrustumSize,
    "light.shadowMinZ": light.shadowMinZ ?? null, "light.shadowMaxZ": light.shadowMaxZ ?? null,
  };
  const other = { shadowGeneratorFilter: filterNames[plain.filter], cameraMaxZ: camera.maxZ, bias: plain.bias,
                  counts: [B.CascadedShadowGenerator.DEFAULT_CASCADES_COUNT, B.CascadedShadowGenerator.MIN_CASCADES_COUNT,
                           B.CascadedShadowGenerator.MAX_CASCADES_COUNT],
                  filterValues: Object.fromEntries(filterNames.map((n) => [n, B.ShadowGenerator[n]])),
                  qualityValues: Object.fromEntries(qualityNames.map((n) => [n, B.ShadowGenerator[n]])) };
  // the setters' clamps and quirks
  const clamps = {};
  for (const v of [1, 6, -3]) { gen.numCascades = v; clamps[`numCascades=${v}`] = gen.numCascades; }
  for (const v of [2, -1, 0.3]) { gen.lambda = v; clamps[`lambda=${v}`] = gen.lambda; }
  for (const v of [3, -0.5, 0.4]) { gen.darkness = v; clamps[`darkness=${v}`] = gen.darkness; }
  for (const v of [0.01, 900, 250]) { gen.shadowMaxZ = v; clamps[`shadowMaxZ=${v}`] = gen.shadowMaxZ; } // below minZ, above maxZ: ignored
  for (const [lo, hi] of [[0.7, 0.3], [-1, 2], [0.1, 0.6]]) { gen.setMinMaxDistance(lo, hi); clamps[`minMax=${lo},${hi}`] = [gen.minDistance, gen.maxDistance]; }
  gen.filter = B.ShadowGenerator.FILTER_EXPONENTIALSHADOWMAP; clamps.csmFilterESM = filterNames[gen.filter];
  gen.dispose(); plain.dispose(); scene.dispose(); engine.dispose();
  return { values, other, clamps };
}

function run(c) {
  const { engine, scene, camera } = makeScene(c);
  const st = c.settings;
  const invView = B.Matrix.Invert(camera.getViewMatrix(true));
  const rows = [];
  for (const l of args.lights) {
    const dirWorld = B.Vector3.TransformNormal(new B.Vector3(-l[0], -l[1], -l[2]), invView); // it shines along -L
    const light = new B.DirectionalLight("sun", dirWorld, scene);
    if (st.class === "ShadowGenerator") {
      light.shadowFrustumSize = st["light.shadowFrustumSize"];
      if (st["light.shadowMinZ"] != null) light.shadowMinZ = st["light.shadowMinZ"];
      if (st["light.shadowMaxZ"] != null) light.shadowMaxZ = st["light.shadowMaxZ"];
      const gen = new B.ShadowGenerator(st.mapSize, light);
      const m = B.Matrix.Zero();
      light.setShadowProjectionMatrix(m, B.Matrix.Identity(), []);
      const side = 2 / m.m[0]; // OrthoLH(width, height, ...): m[0] = 2/width, m[5] = 2/height, m[10] = 2/(far − near) in WebGL
      rows.push({ texels: [[side / st.mapSize, 2 / m.m[5] / st.mapSize]], depth: [2 / m.m[10]] });
      gen.dispose();
      light.dispose();
      continue;
    }
    const gen = new B.CascadedShadowGenerator(st.mapSize, light, undefined, camera);
    for (const k of ["numCascades", "lambda", "stabilizeCascades", "shadowMaxZ"]) {
      if (k in st && st[k] !== null) gen[k] = st[k];
    }
    if ("minDistance" in st || "maxDistance" in st) gen.setMinMaxDistance(st.minDistance ?? 0, st.maxDistance ?? 1);
    // casters everywhere: the cascade's light near..far stays its box's extent along the light
    gen.shadowCastersBoundingInfo = new B.BoundingInfo(new B.Vector3(-1e9, -1e9, -1e9), new B.Vector3(1e9, 1e9, 1e9));
    gen._splitFrustum();
    gen._computeMatrices();
    const texels = [];
    const depth = [];
    for (let i = 0; i < gen.numCascades; i++) {
      const lo = gen.getCascadeMinExtents(i), hi = gen.getCascadeMaxExtents(i);
      texels.push([(hi.x - lo.x) / st.mapSize, (hi.y - lo.y) / st.mapSize]);
      depth.push(hi.z - lo.z);
    }
    rows.push({ texels, depth });
    gen.dispose();
    light.dispose();
  }
  scene.dispose();
  engine.dispose();
  return { rows };
}

process.stdout.write(JSON.stringify({ version: B.Engine.Version, defaults: defaults(), cases: args.cases.map(run) }) + "\n");
