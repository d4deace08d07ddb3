// PlayCanvas's own frame: a directional light with cascaded shadows, read back per pixel.
//
// window.frame(job) renders the job's scene (a triangle soup in a right-handed, y-up world, as
// PlayCanvas's own) and returns what the engine computed, as the three.js page does:
//   shadow    per pixel: the value getShadow0 returned and lightFunctionLight multiplied into
//             dAtten (after the shadow intensity), the cascade getShadow0 picked
//   position  per pixel: vPositionW;  normal: dVertexNormalW turned towards the eye
//   cascades  per cascade: the shadow matrix palette entry, map size (the atlas cell)
//   path      (job.path) per pose: the factor with the maps fitted to a camera at that pose
//             (the picture's camera stays: drawn once at the pose for the maps, once in place
//             for the factor, the maps kept), and the palette
//   maps      (job.maps) the shadow atlas as last drawn, every stride-th texel, with its palette
// The statements are added to the material's own shader chunks (lightFunctionLightPS,
// lightFunctionShadowPS) and the outputs written in its outputPS chunk.
import * as pc from "/node_modules/playcanvas/build/playcanvas.mjs";
import { decodeF32, encode, flatNormals, readDepthTexture } from "./common.mjs";

const DECL = "#ifndef FRAMES_DECL\n#define FRAMES_DECL\nfloat frShadow = 1.0;\nfloat frCascade = -1.0;\n#endif\n";

function chunks(material, mode) {
  const glsl = material.getShaderChunks(pc.SHADERLANGUAGE_GLSL);
  const all = pc.ShaderChunks.get(material.device ?? window.frameDevice, pc.SHADERLANGUAGE_GLSL);
  const light = all.get("lightFunctionLightPS"), shadow = all.get("lightFunctionShadowPS");
  const atten = "dAtten *= shadow;";
  const pick = "mat4 shadowMatrix = light{i}_shadowMatrixPalette[cascadeIndex];";
  const single = "mat4 shadowMatrix = light{i}_shadowMatrix;";
  if (!light.includes(atten) || !shadow.includes(pick)) throw new Error("PlayCanvas lighting chunks: the shadow statements to capture were not found");
  glsl.set("lightFunctionShadowPS", DECL + shadow.replace(pick, pick + "\nfrCascade = float(cascadeIndex);").replace(single, single + "\nfrCascade = 0.0;"));
  glsl.set("lightFunctionLightPS", DECL + light.replace(atten, atten + "\nfrShadow = shadow;"));
  const out = mode === 1 ? "gl_FragColor = vec4(frShadow, frCascade, 0.0, 1.0);"
    : mode === 2 ? "gl_FragColor = vec4(vPositionW, 1.0);"
    : mode === 3 ? "gl_FragColor = vec4(gl_FrontFacing ? dVertexNormalW : -dVertexNormalW, 1.0);" : "";
  glsl.set("outputPS", out);
  material.shaderChunksVersion = "2.23";
}

const LIGHT_KEYS = ["shadowBias", "normalOffsetBias", "shadowResolution", "numCascades", "cascadeDistribution", "cascadeBlend", "shadowDistance",
  "shadowType", "shadowIntensity", "shadowUpdateMode"];

window.frame = async (job) => {
  const w = job.width, h = job.height, s = job.settings;
  const canvas = document.createElement("canvas");
  canvas.width = w; canvas.height = h;
  document.body.appendChild(canvas);
  const device = await pc.createGraphicsDevice(canvas, { deviceTypes: [pc.DEVICETYPE_WEBGL2], antialias: false, preserveDrawingBuffer: true, alpha: false });
  if (!device.isWebGL2) throw new Error("no WebGL 2 context");
  if (!device.textureFloatRenderable) throw new Error("WebGL 2 without float render targets: float read-back impossible");
  window.frameDevice = device;
  device.maxPixelRatio = 1;
  const app = new pc.Application(canvas, { graphicsDevice: device });
  app.setCanvasFillMode(pc.FILLMODE_NONE);
  app.setCanvasResolution(pc.RESOLUTION_FIXED, w, h);
  app.autoRender = false;
  app.scene.ambientLight = new pc.Color(0.25, 0.25, 0.25);

  const c = job.camera;
  const camera = new pc.Entity("camera");
  camera.addComponent("camera", { fov: c.fov, nearClip: c.near, farClip: c.far, clearColor: new pc.Color(0, 0, 0, 0), horizontalFov: false });
  camera.setPosition(...c.eye);
  camera.lookAt(new pc.Vec3(...c.target), new pc.Vec3(...c.up));
  app.root.addChild(camera);

  const sun = new pc.Vec3(...job.sun).normalize();          // the light shines along its entity's -Y: turn +Y onto the sun
  const yAxis = new pc.Vec3(0, 1, 0);
  const axis = new pc.Vec3().cross(yAxis, sun);
  const q = new pc.Quat();
  if (axis.length() < 1e-9) q.setFromAxisAngle(new pc.Vec3(1, 0, 0), sun.y > 0 ? 0 : 180);
  else q.setFromAxisAngle(axis.normalize(), Math.acos(Math.max(-1, Math.min(1, yAxis.dot(sun)))) * 180 / Math.PI);
  const light = new pc.Entity("sun");
  const opts = { type: "directional", castShadows: true, intensity: 1, color: new pc.Color(1, 1, 1) };
  for (const k of LIGHT_KEYS) if (s[k] !== undefined) opts[k] = s[k];
  light.addComponent("light", opts);
  light.setRotation(q);
  app.root.addChild(light);

  const pos = decodeF32(job.triangles);
  const mesh = new pc.Mesh(device);
  mesh.setPositions(pos);
  mesh.setNormals(flatNormals(pos));
  mesh.setIndices(Uint32Array.from({ length: pos.length / 3 }, (_, i) => i));
  mesh.update();
  const materials = [0, 1, 2, 3].map((mode) => {
    const m = new pc.StandardMaterial();
    m.diffuse = new pc.Color(1, 1, 1);
    m.specular = new pc.Color(0, 0, 0);
    m.useMetalness = false;
    m.gloss = 0;
    if (s.cull !== undefined) m.cull = { back: pc.CULLFACE_BACK, front: pc.CULLFACE_FRONT, none: pc.CULLFACE_NONE }[s.cull];
    if (mode > 0) chunks(m, mode);
    m.update();
    return m;
  });
  const mi = new pc.MeshInstance(mesh, materials[0]);
  const entity = new pc.Entity("scene");
  entity.addComponent("render", { meshInstances: [mi], castShadows: true, receiveShadows: true });
  app.root.addChild(entity);

  const t0 = performance.now();
  app.start();
  app.render();                                             // the engine's own frame (shadow maps drawn here)
  const frame = canvas.toDataURL("image/png");
  const tex = new pc.Texture(device, { width: w, height: h, format: pc.PIXELFORMAT_RGBA32F, mipmaps: false,
                                       minFilter: pc.FILTER_NEAREST, magFilter: pc.FILTER_NEAREST });
  const rt = new pc.RenderTarget({ colorBuffer: tex, depth: true });
  camera.camera.renderTarget = rt;
  light.light.shadowUpdateMode = pc.SHADOWUPDATE_NONE;       // the read-back passes reuse the frame's maps
  const out = {};
  for (const [mode, name] of [[1, "shadow"], [2, "position"], [3, "normal"]]) {
    mi.material = materials[mode];
    app.render();
    const px = await tex.read(0, 0, w, h, { renderTarget: rt, immediate: true });
    out[name] = encode(new Float32Array(px.buffer, px.byteOffset, w * h * 4));
  }
  const L = light.light.light;
  const palette16 = () => Array.from({ length: L.numCascades }, (_, i) => Array.from(L._shadowMatrixPalette.slice(16 * i, 16 * i + 16)));
  const size = L.shadowResolution;
  const cascades = palette16().map((matrix, i) => ({ matrix, size: [size, size], distance: L._shadowCascadeDistances[i] }));
  // a camera path: the cascades follow the camera drawn at each pose (app.render with the maps
  // updated), then the picture's camera, back in place, draws the factor with those maps kept, so
  // every pixel keeps its world point and a change of its factor is the maps' motion alone
  const path = [];
  if (job.path) {
    mi.material = materials[1];
    const target = new pc.Vec3(...c.target), up = new pc.Vec3(...c.up);
    for (const pose of job.path) {
      camera.setPosition(...pose.eye);
      camera.lookAt(new pc.Vec3(...pose.target), up);
      light.light.shadowUpdateMode = pc.SHADOWUPDATE_REALTIME;
      app.render();                                         // the maps and the palette fitted to this pose
      camera.setPosition(...c.eye);
      camera.lookAt(target, up);
      light.light.shadowUpdateMode = pc.SHADOWUPDATE_NONE;
      app.render();
      const px = await tex.read(0, 0, w, h, { renderTarget: rt, immediate: true });
      const buf = new Float32Array(px.buffer, px.byteOffset, w * h * 4);
      const factor = new Float32Array(w * h);
      for (let i = 0; i < w * h; i++) factor[i] = buf[4 * i];
      path.push({ shadow: encode(factor), matrices: palette16() });
    }
  }
  // the shadow atlas as last drawn (the DEPTH_COMPONENT32F texture the PCF lookup samples), read
  // last: the pass changes GL state behind the engine's caches and the app is destroyed after it
  let maps = null;
  if (job.maps) {
    const atlas = L._shadowMap.texture, size = atlas.width, stride = Math.max(1, Math.ceil(size / job.maps.side));
    const got = readDepthTexture(device.gl, atlas.impl._glTexture, size, stride, null);
    maps = [{ depth: got.maps[0], side: got.side, stride, size, matrices: palette16() }];
  }
  const ms = performance.now() - t0;
  const used = {};
  for (const k of LIGHT_KEYS) used[k] = light.light[k];
  const gl = device.gl;
  const dbg = gl.getExtension("WEBGL_debug_renderer_info");
  const res = { engine: "playcanvas", revision: pc.version, width: w, height: h, frame, ...out, cascades, used, ms, path, maps,
                renderer: dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER) };
  app.destroy();
  return res;
};
