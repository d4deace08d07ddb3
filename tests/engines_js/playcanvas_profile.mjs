// Runs PlayCanvas's own LightComponent, Light and ShadowRendererDirectional (the pinned `playcanvas`
// package's ES modules, build/playcanvas/src) in node on a NullGraphicsDevice for the toolkit's
// PlayCanvas profile (aliasing/setups/playcanvas.py) and prints, as JSON on stdout:
//   defaults: a new LightComponent's values for the profile's setting keys, what its setters make of
//             out-of-range values, the depth bias the light hands to the caster pass, a new material's cull;
//   cases:    per case, each cascade's end, texel (2·orthoHeight ÷ its viewport's texels) and the
//             radius of its sphere.
//
// usage: node playcanvas_profile.mjs PACKAGE_ROOT JSON
//   JSON {"cases": [{"near", "far", "fov" (vertical, deg), "aspect", "settings": {profile keys: values}}, ...]}
// The fit is a sphere (the light's direction does not change the box): one light direction is run.
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root, text] = process.argv.slice(2);
const args = JSON.parse(text);
const src = (p) => import(pathToFileURL(path.join(root, "node_modules", "playcanvas", "build", "playcanvas", "src", p)).href);
const { NullGraphicsDevice } = await src("platform/graphics/null/null-graphics-device.js");
const { LightComponent } = await src("framework/components/light/component.js");
const { Entity } = await src("framework/entity.js");
const { StandardMaterial } = await src("scene/materials/standard-material.js");
const { Camera } = await src("scene/camera.js");
const { GraphNode } = await src("scene/graph-node.js");
const { ShadowRendererDirectional } = await src("scene/renderer/shadow-renderer-directional.js");
const C = await src("scene/constants.js");
const G = await src("platform/graphics/constants.js");

const device = new NullGraphicsDevice({ width: 1, height: 1 });
device.maxTextureSize = 16384;
const system = { app: { graphicsDevice: device, scene: { clusteredLightingEnabled: false } } };
const KEYS = ["castShadows", "numCascades", "cascadeDistribution", "cascadeBlend", "shadowDistance", "shadowResolution", "shadowBias",
  "normalOffsetBias", "shadowType", "vsmBlurSize", "vsmBlurMode", "vsmBias", "shadowSamples", "penumbraSize", "penumbraFalloff", "shadowIntensity"];
const TYPES = ["SHADOW_PCF3_32F", "SHADOW_VSM_16F", "SHADOW_VSM_32F", "SHADOW_PCF5_32F", "SHADOW_PCF1_32F", "SHADOW_PCSS_32F",
  "SHADOW_PCF1_16F", "SHADOW_PCF3_16F", "SHADOW_PCF5_16F"];
const CULLS = ["CULLFACE_NONE", "CULLFACE_BACK", "CULLFACE_FRONT"];

function component(settings = {}) {
  const c = new LightComponent(system, new Entity("sun"));
  for (const [k, v] of Object.entries(settings)) {
    if (k === "shadowType" || k === "vsmBlurMode") c[k] = C[v];
    else if (KEYS.includes(k)) c[k] = v;
  }
  return c;
}

function defaults() {
  const c = component();
  const values = Object.fromEntries(KEYS.map((k) => [k, c[k]]));
  values.shadowType = TYPES.find((n) => C[n] === c.shadowType);
  values.vsmBlurMode = ["BLUR_BOX", "BLUR_GAUSSIAN"].find((n) => C[n] === c.vsmBlurMode);
  values["material.cull"] = CULLS.find((n) => G[n] === new StandardMaterial().cull);
  const light = c.light;
  const bias = { light: light.shadowBias, constant: light.shadowDepthState.depthBias, slope: light.shadowDepthState.depthBiasSlope };
  const clamps = {};
  const probe = { numCascades: [0, 7, 2.7], cascadeDistribution: [-1, 2], cascadeBlend: [-0.5, 1.5], shadowBias: [-1, 3, 0.2],
                  normalOffsetBias: [-1, 2], vsmBias: [-1, 2] };
  for (const [k, vs] of Object.entries(probe)) {
    for (const v of vs) {
      const d = component({ [k]: v });
      clamps[`${k}=${v}`] = k === "shadowBias" ? [d.light.shadowBias, d.light.shadowDepthState.depthBias] : d[k];
    }
  }
  return { values, bias, clamps, constants: Object.fromEntries(TYPES.map((n) => [n, C[n]])) };
}

function run(c) {
  const comp = component(c.settings);
  const light = comp.light;
  light._node.setEulerAngles(-60, 30, 0);
  light.castShadows = true;
  const camera = new Camera();
  camera.node = new GraphNode("eye");
  camera.aspectRatioMode = C.ASPECT_MANUAL;
  camera.nearClip = c.near;
  camera.farClip = c.far;
  camera.fov = c.fov;
  camera.aspectRatio = c.aspect;
  const renderer = new ShadowRendererDirectional({ device }, { cullShadowCasters() {} });
  renderer.cull(light, null, camera);
  const cascades = [];
  for (let i = 0; i < light.numCascades; i++) {
    const rd = light.getRenderData(camera, i);
    const cam = rd.shadowCamera;
    cascades.push({ end: light._shadowCascadeDistances[i], radius: cam.orthoHeight, aspect: cam.aspectRatio,
                    texel: (2 * cam.orthoHeight * cam.aspectRatio) / (rd.shadowViewport.z * light.shadowResolution),
                    texel_y: (2 * cam.orthoHeight) / (rd.shadowViewport.w * light.shadowResolution) });
  }
  return { cascades };
}

process.stdout.write(JSON.stringify({ defaults: defaults(), cases: args.cases.map(run) }) + "\n");
