// Filament's own frame (npm `filament`, WebGL 2): a DIRECTIONAL light with shadows, read back per pixel.
//
// The npm package has no material compiler (matc), so no material can output the shadow factor
// itself.  The page renders the job's scene (a glTF built here from the job's triangles and loaded
// through gltfio's built-in ubershader materials: white, metallic 0, roughness 1) twice with the
// same camera, light and shadow maps:
//   lit       every renderable receives shadows (the engine's frame)
//   unlit     every renderable's receiveShadows is false
// with post-processing off (no tone mapping, no dithering, no anti-aliasing), the exposure set
// directly (Camera.setExposureDirect(1)) and an indirect light of intensity 0, so that each
// drawn pixel's colour is BRDF · intensity · N·L · visibility in both frames and the shadow
// factor is their ratio (computed in Python from the 8-bit colours, aliasing.frames.models.Filament).
// Per pixel positions and normals are not readable without a custom material: the toolkit
// rasterizes the scene through the camera read back here (projection and view matrices).
// window.frame(job) returns
//   lit, unlit   base64 RGBA8 of the two frames (rows bottom-up, as WebGL reads them)
//   projection, view   the camera's matrices as Filament holds them (column-major)
//   shadowOptions   Filament.shadowOptions of the settings (the binding's defaults: the light keeps them)
import { decodeF32 } from "./common.mjs";

const OPTIONS = ["mapSize", "shadowCascades", "constantBias", "normalBias", "shadowFar", "shadowNearHint", "shadowFarHint", "stable",
  "polygonOffsetConstant", "polygonOffsetSlope", "screenSpaceContactShadows", "stepCount", "maxShadowDistance"];
export const ALBEDO = 0.8;   // white enough, and below 1 so that lit colours stay under 255

let ready = null;
function load() {
  if (!ready) {
    ready = new Promise((resolve, reject) => {
      const s = document.createElement("script");
      s.src = "/node_modules/filament/filament.js";
      s.onload = () => window.Filament.init([], resolve);
      s.onerror = () => reject(new Error("filament.js did not load"));
      document.head.appendChild(s);
    });
  }
  return ready;
}

// a GLB of the triangle soup: positions, flat normals, a lit material (metallic 0, roughness 1)
function glb(pos, doubleSided) {
  const n = pos.length / 3;
  const nrm = new Float32Array(pos.length);
  for (let t = 0; t < pos.length; t += 9) {
    const ax = pos[t + 3] - pos[t], ay = pos[t + 4] - pos[t + 1], az = pos[t + 5] - pos[t + 2];
    const bx = pos[t + 6] - pos[t], by = pos[t + 7] - pos[t + 1], bz = pos[t + 8] - pos[t + 2];
    let x = ay * bz - az * by, y = az * bx - ax * bz, z = ax * by - ay * bx;
    const l = Math.hypot(x, y, z) || 1;
    for (let k = 0; k < 3; k++) { nrm[t + 3 * k] = x / l; nrm[t + 3 * k + 1] = y / l; nrm[t + 3 * k + 2] = z / l; }
  }
  const idx = Uint32Array.from({ length: n }, (_, i) => i);
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < pos.length; i++) { min[i % 3] = Math.min(min[i % 3], pos[i]); max[i % 3] = Math.max(max[i % 3], pos[i]); }
  const L = pos.byteLength;
  const json = {
    asset: { version: "2.0" }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [ALBEDO, ALBEDO, ALBEDO, 1], metallicFactor: 0, roughnessFactor: 1 }, doubleSided }],
    accessors: [{ bufferView: 0, componentType: 5126, count: n, type: "VEC3", min, max },
      { bufferView: 1, componentType: 5126, count: n, type: "VEC3" },
      { bufferView: 2, componentType: 5125, count: n, type: "SCALAR" }],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: L }, { buffer: 0, byteOffset: L, byteLength: L }, { buffer: 0, byteOffset: 2 * L, byteLength: idx.byteLength }],
    buffers: [{ byteLength: 2 * L + idx.byteLength }],
  };
  let text = new TextEncoder().encode(JSON.stringify(json));
  const pad = (4 - (text.length % 4)) % 4;
  const jlen = text.length + pad, blen = 2 * L + idx.byteLength;
  const out = new Uint8Array(12 + 8 + jlen + 8 + blen);
  const dv = new DataView(out.buffer);
  dv.setUint32(0, 0x46546c67, true); dv.setUint32(4, 2, true); dv.setUint32(8, out.length, true);
  dv.setUint32(12, jlen, true); dv.setUint32(16, 0x4e4f534a, true);
  out.set(text, 20); out.fill(0x20, 20 + text.length, 20 + jlen);
  const b0 = 20 + jlen;
  dv.setUint32(b0, blen, true); dv.setUint32(b0 + 4, 0x004e4942, true);
  out.set(new Uint8Array(pos.buffer, pos.byteOffset, L), b0 + 8);
  out.set(new Uint8Array(nrm.buffer), b0 + 8 + L);
  out.set(new Uint8Array(idx.buffer), b0 + 8 + 2 * L);
  return out;
}

const nextFrame = () => new Promise((r) => requestAnimationFrame(() => r()));

function pixels(canvas, w, h) {
  // the canvas (preserveDrawingBuffer) drawn into a 2D canvas: RGBA8, rows flipped to bottom-up
  const c2 = document.createElement("canvas");
  c2.width = w; c2.height = h;
  const ctx = c2.getContext("2d", { willReadFrequently: true });
  ctx.drawImage(canvas, 0, 0);
  const top = ctx.getImageData(0, 0, w, h).data;
  const out = new Uint8Array(w * h * 4);
  for (let j = 0; j < h; j++) out.set(top.subarray((h - 1 - j) * w * 4, (h - j) * w * 4), j * w * 4);
  return out;
}

function b64(bytes) {
  let s = "";
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

window.frame = async (job) => {
  await load();
  const F = window.Filament;
  const w = job.width, h = job.height, s = job.settings;
  const canvas = document.createElement("canvas");
  canvas.width = w; canvas.height = h;
  document.body.appendChild(canvas);
  const engine = F.Engine.create(canvas, { preserveDrawingBuffer: true, antialias: false, alpha: false });
  const scene = engine.createScene();
  const renderer = engine.createRenderer();
  const camera = engine.createCamera(F.EntityManager.get().create());
  const view = engine.createView();
  const swap = engine.createSwapChain();
  view.setCamera(camera); view.setScene(scene);
  view.setViewport([0, 0, w, h]);
  view.setPostProcessingEnabled(false);
  renderer.setClearOptions({ clearColor: [0, 0, 1, 1], clear: true });   // blue: no surface

  const c = job.camera;
  camera.setProjectionFov(c.fov, w / h, c.near, c.far, F.Camera$Fov.VERTICAL);
  camera.lookAt(c.eye, c.target, c.up);
  camera.setExposureDirect(1.0);

  const ibl = F.IndirectLight.Builder().irradianceSh(1, new Float32Array([0, 0, 0])).intensity(0).build(engine);
  scene.setIndirectLight(ibl);                                          // no ambient: colour = direct light only

  const options = {};
  const defaults = F.shadowOptions({});
  for (const k of OPTIONS) if (s[k] !== undefined && s[k] !== defaults[k]) options[k] = s[k];
  const sun = F.EntityManager.get().create();
  F.LightManager.Builder(F.LightManager$Type.DIRECTIONAL).color([1, 1, 1]).intensity(Math.PI).direction([-job.sun[0], -job.sun[1], -job.sun[2]])
    .castShadows(true).build(engine, sun);
  if (Object.keys(options).length) {
    // 1.53.4's binding registers neither Builder.shadowOptions nor LightManager.setShadowOptions'
    // argument type ("unbound types"): the light keeps the C++ ShadowOptions defaults
    const lm = engine.getLightManager();
    const li = lm.getInstance(sun);
    try { lm.setShadowOptions(li, options); } finally { li.delete(); }
  }
  scene.addEntity(sun);

  const loader = engine.createAssetLoader();
  const asset = loader.createAsset(glb(decodeF32(job.triangles), !!s.doubleSided));
  if (!asset) throw new Error("Filament's gltfio could not load the scene");
  asset.loadResources();
  const entities = asset.getRenderableEntities();
  scene.addEntities(entities);
  const rm = engine.getRenderableManager();

  const t0 = performance.now();
  const draw = async (receive) => {
    for (const e of entities) { const inst = rm.getInstance(e); rm.setReceiveShadows(inst, receive); rm.setCastShadows(inst, true); inst.delete(); }
    // a frame Filament skips (beginFrame false) is not drawn: draw `settle` frames (default 1), then read
    let drawn = 0, tries = 0;
    while (drawn < (job.settle ?? 1) && tries++ < 200) {
      if (renderer.beginFrame(swap)) { renderer.renderView(view); renderer.endFrame(); drawn++; }
      engine.execute();
      await nextFrame();
    }
    if (drawn === 0) throw new Error("Filament drew no frame (beginFrame kept returning false)");
    return pixels(canvas, w, h);
  };
  const lit = await draw(true);
  const unlit = await draw(false);
  const again = await draw(true);                                       // the lit frame again: is it settled?
  let changed = 0;
  for (let i = 0; i < lit.length; i++) if (lit[i] !== again[i]) changed++;
  const ms = performance.now() - t0;
  const frame = canvas.toDataURL("image/png");
  const gl = canvas.getContext("webgl2");
  const dbg = gl && gl.getExtension("WEBGL_debug_renderer_info");
  const res = { engine: "filament", revision: "1.53.4", width: w, height: h, frame, lit: b64(lit), unlit: b64(unlit), relit_changed: changed,
                projection: Array.from(camera.getProjectionMatrix()), view: Array.from(camera.getViewMatrix()),
                shadowOptions: F.shadowOptions(options), albedo: ALBEDO, ms, cascades: [],
                renderer: dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : (gl ? gl.getParameter(gl.RENDERER) : "") };
  return res;
};
