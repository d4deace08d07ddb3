// Babylon.js's own frame: CascadedShadowGenerator on a DirectionalLight, read back per pixel.
//
// window.frame(job) renders the job's scene (a triangle soup in a right-handed, y-up world) and
// returns what the engine computed, as the three.js page does.  Babylon.js keeps its default
// left-handed system: the page mirrors the world in z (which also turns the job's counter-
// clockwise outside faces into Babylon's clockwise front faces) and mirrors everything it reads
// back (positions, normals, light matrices) into the job's world.
//   shadow    per pixel: StandardMaterial's aggShadow (with one light: the shadow factor that
//             light's diffuse was multiplied by, cascade blending included), the cascade the
//             lightFragment loop picked (before blending), n·l
//   position  per pixel: vPositionW;  normal: normalW turned towards the eye
//   cascades  per cascade: getCascadeTransformMatrix (world -> clip, row vectors), map size, view z
// The cascade index is captured by adding one statement after lightFragment's selection loop;
// the outputs are written by a MaterialPluginBase at CUSTOM_FRAGMENT_MAIN_END.
import { Engine } from "/node_modules/@babylonjs/core/Engines/engine.js";
import { Scene } from "/node_modules/@babylonjs/core/scene.js";
import { FreeCamera } from "/node_modules/@babylonjs/core/Cameras/freeCamera.js";
import { DirectionalLight } from "/node_modules/@babylonjs/core/Lights/directionalLight.js";
import { CascadedShadowGenerator } from "/node_modules/@babylonjs/core/Lights/Shadows/cascadedShadowGenerator.js";
import { ShadowGenerator } from "/node_modules/@babylonjs/core/Lights/Shadows/shadowGenerator.js";
import "/node_modules/@babylonjs/core/Lights/Shadows/shadowGeneratorSceneComponent.js";
import { Mesh } from "/node_modules/@babylonjs/core/Meshes/mesh.js";
import { VertexData } from "/node_modules/@babylonjs/core/Meshes/mesh.vertexData.js";
import { StandardMaterial } from "/node_modules/@babylonjs/core/Materials/standardMaterial.js";
import { MaterialPluginBase } from "/node_modules/@babylonjs/core/Materials/materialPluginBase.js";
import { RenderTargetTexture } from "/node_modules/@babylonjs/core/Materials/Textures/renderTargetTexture.js";
import { Vector3 } from "/node_modules/@babylonjs/core/Maths/math.vector.js";
import { Color3, Color4 } from "/node_modules/@babylonjs/core/Maths/math.color.js";
import { Constants } from "/node_modules/@babylonjs/core/Engines/constants.js";
import { ShaderStore } from "/node_modules/@babylonjs/core/Engines/shaderStore.js";
import "/node_modules/@babylonjs/core/Shaders/default.fragment.js";
import "/node_modules/@babylonjs/core/Shaders/default.vertex.js";
import "/node_modules/@babylonjs/core/Shaders/ShadersInclude/lightFragment.js";
import { decodeF32, encode, flatNormals, readDepthTexture } from "./common.mjs";

const PICK = "if (diff{X}>=0.) {index{X}=i;break;}}";

function instrument() {
  const store = ShaderStore.IncludesShadersStore;
  if (store.lightFragment.includes("frCascade")) return;
  if (!store.lightFragment.includes(PICK)) throw new Error("Babylon.js lightFragment: the cascade selection loop was not found to capture");
  store.lightFragment = store.lightFragment.replace(PICK, PICK + "\n#ifdef FRAMES_CASCADE\nfrCascade=float(index{X});\n#endif\n");
}

class ReadBack extends MaterialPluginBase {
  constructor(material, mode, single) {
    super(material, `FramesReadBack${mode}`, 200, { [`FRAMES_MODE${mode}`]: true, FRAMES_CASCADE: true }, true, true);
    this.mode = mode;
    this.single = single;                                 // one ShadowGenerator map: cascade 0
    this._enable(true);
  }
  prepareDefines(defines) { defines[`FRAMES_MODE${this.mode}`] = true; defines.FRAMES_CASCADE = true; }
  getClassName() { return `FramesReadBack${this.mode}`; }
  getCustomCode(shaderType) {
    if (shaderType !== "fragment") return null;
    const out = this.mode === 1 ? "gl_FragColor=vec4(aggShadow,frCascade,0.,1.);"
      : this.mode === 2 ? "gl_FragColor=vec4(vPositionW.xy,-vPositionW.z,1.);"
      : this.mode === 3 ? "vec3 frN=gl_FrontFacing?normalW:-normalW;gl_FragColor=vec4(frN.xy,-frN.z,1.);" : "";
    return { CUSTOM_FRAGMENT_DEFINITIONS: this.single ? "float frCascade=0.;" : "float frCascade=-1.;", CUSTOM_FRAGMENT_MAIN_END: out };
  }
}

const GEN_KEYS = ["bias", "normalBias", "darkness", "frustumEdgeFalloff", "numCascades", "lambda", "stabilizeCascades", "cascadeBlendPercentage",
  "depthClamp", "autoCalcDepthBounds", "shadowMaxZ", "filteringQuality", "usePercentageCloserFiltering", "forceBackFacesOnly", "penumbraDarkness"];

window.frame = async (job) => {
  const w = job.width, h = job.height, s = job.settings;
  const canvas = document.createElement("canvas");
  canvas.width = w; canvas.height = h;
  document.body.appendChild(canvas);
  const engine = new Engine(canvas, false, { preserveDrawingBuffer: true, stencil: true, antialias: false });
  if (engine.webGLVersion !== 2) throw new Error("no WebGL 2 context");
  if (!engine.getCaps().textureFloatRender) throw new Error("WebGL 2 without float render targets: float read-back impossible");
  engine.setHardwareScalingLevel(1);
  instrument();
  const scene = new Scene(engine);
  scene.clearColor = new Color4(0, 0, 0, 0);

  const c = job.camera;
  const mz = (v) => new Vector3(v[0], v[1], -v[2]);  // the job's right-handed world -> Babylon's left-handed one
  const camera = new FreeCamera("camera", mz(c.eye), scene);
  camera.upVector = mz(c.up);
  camera.setTarget(mz(c.target));
  camera.fov = c.fov * Math.PI / 180;
  camera.minZ = c.near; camera.maxZ = c.far;
  scene.activeCamera = camera;

  const light = new DirectionalLight("sun", mz([-job.sun[0], -job.sun[1], -job.sun[2]]), scene);
  light.intensity = 1;
  const mapSize = s.mapSize ?? 1024;
  const single = s.class === "ShadowGenerator";
  let csm;
  if (single) {
    // one ShadowGenerator: a fixed square box (light.shadowFrustumSize) around the light, looking
    // along its direction, depth shadowMinZ..shadowMaxZ from it (DirectionalLight
    // _setDefaultFixedFrustumShadowProjectionMatrix); the page puts the light (minZ + maxZ)/2
    // from job.lightTarget towards the sun
    const lo = s.shadowMinZ ?? c.near, hi = s.shadowMaxZ ?? c.far, t = job.lightTarget, d = (lo + hi) / 2;
    light.position = mz([t[0] + job.sun[0] * d, t[1] + job.sun[1] * d, t[2] + job.sun[2] * d]);
    light.shadowFrustumSize = s.shadowFrustumSize;
    if (s.shadowMinZ !== null && s.shadowMinZ !== undefined) light.shadowMinZ = s.shadowMinZ;
    if (s.shadowMaxZ !== null && s.shadowMaxZ !== undefined) light.shadowMaxZ = s.shadowMaxZ;
    csm = new ShadowGenerator(mapSize, light);
    for (const k of ["bias", "normalBias", "darkness", "frustumEdgeFalloff", "forceBackFacesOnly"]) if (s[k] !== undefined) csm[k] = s[k];
  } else {
    csm = new CascadedShadowGenerator(mapSize, light);
    for (const k of GEN_KEYS) if (s[k] !== undefined) csm[k] = s[k];
  }

  const pos = decodeF32(job.triangles);
  const nrm = flatNormals(pos);                        // outward, in the job's world
  for (let i = 2; i < pos.length; i += 3) { pos[i] = -pos[i]; nrm[i] = -nrm[i]; }
  const mesh = new Mesh("scene", scene);
  const vd = new VertexData();
  vd.positions = Array.from(pos);
  vd.normals = Array.from(nrm);
  vd.indices = Array.from({ length: pos.length / 3 }, (_, i) => i);
  vd.applyToMesh(mesh);
  mesh.receiveShadows = true;
  mesh.alwaysSelectAsActiveMesh = true;
  csm.addShadowCaster(mesh);
  const materials = [0, 1, 2, 3].map((mode) => {
    const m = new StandardMaterial(`m${mode}`, scene);
    m.diffuseColor = new Color3(1, 1, 1);
    m.specularColor = new Color3(0, 0, 0);
    if (mode === 0) m.emissiveColor = new Color3(0.25, 0.25, 0.25);  // the frame only: shadows not black (one light: aggShadow is its factor)
    if (s.backFaceCulling !== undefined) m.backFaceCulling = s.backFaceCulling;
    if (mode > 0) new ReadBack(m, mode, single);
    return m;
  });
  mesh.material = materials[0];

  const t0 = performance.now();
  await scene.whenReadyAsync();
  scene.render();                                       // the engine's own frame (shadow maps drawn here)
  const frame = canvas.toDataURL("image/png");
  const rtt = new RenderTargetTexture("readback", { width: w, height: h }, scene, false, true, Constants.TEXTURETYPE_FLOAT);
  rtt.renderList = [mesh];
  rtt.activeCamera = camera;
  rtt.clearColor = new Color4(0, 0, 0, 0);
  csm.getShadowMap().refreshRate = 0;                   // the read-back passes reuse the frame's maps
  const out = {};
  for (const [mode, name] of [[1, "shadow"], [2, "position"], [3, "normal"]]) {
    mesh.material = materials[mode];
    await new Promise((resolve) => { const check = () => (materials[mode].isReady(mesh) ? resolve() : setTimeout(check, 10)); check(); });
    rtt.render();
    const px = await rtt.readPixels(0, 0, null, true, false);
    out[name] = encode(new Float32Array(px.buffer, px.byteOffset, w * h * 4));
  }
  // the shadow maps as drawn for this frame: the depth-stencil texture array the PCF lookup samples
  // (job.maps: every stride-th texel, at most job.maps.side per side)
  let maps = null;
  if (job.maps) {
    const depthTex = csm.getShadowMap().depthStencilTexture;
    const stride = Math.max(1, Math.ceil(mapSize / job.maps.side));
    const got = readDepthTexture(engine._gl, depthTex._hardwareTexture.underlyingResource, mapSize, stride, csm.numCascades);
    maps = got.maps.map((m) => ({ depth: m, side: got.side, stride, size: mapSize }));
    engine.wipeCaches(true);                            // Babylon.js's cached GL state: the pass above changed it
  }
  const ms = performance.now() - t0;
  const cascades = [];
  if (single) {
    const m = Array.from(csm.getTransformMatrix().m);            // row vectors: clip = [x y z 1] m (Babylon's world)
    for (let j = 8; j < 12; j++) m[j] = -m[j];
    cascades.push({ matrix: m, clip: true, size: [mapSize, mapSize], viewZ: c.far });
  }
  for (let i = 0; i < (single ? 0 : csm.numCascades); i++) {
    const m = Array.from(csm.getCascadeTransformMatrix(i).m);  // row vectors: clip = [x y z 1] m (Babylon's world)
    for (let j = 8; j < 12; j++) m[j] = -m[j];                    // the row taking z: the job's world
    cascades.push({ matrix: m, clip: true, size: [mapSize, mapSize], viewZ: csm._viewSpaceFrustumsZ[i],
                    length: csm._frustumLengths[i], min: csm.getCascadeMinExtents(i).asArray(), max: csm.getCascadeMaxExtents(i).asArray() });
  }
  // a camera path: the cascades follow a second camera moving along it (the generator's camera)
  // while the picture's camera stays, so every pixel keeps its world point and a change of its
  // factor is the maps' motion alone
  const path = [];
  if (job.path) {
    const fit = new FreeCamera("fit", mz(c.eye), scene);
    fit.upVector = mz(c.up); fit.fov = camera.fov; fit.minZ = camera.minZ; fit.maxZ = camera.maxZ;
    csm._camera = fit;                                  // ShadowGenerator._getCamera: this._camera ?? scene.activeCamera
    mesh.material = materials[1];
    const sm = csm.getShadowMap();
    for (const pose of job.path) {
      fit.position = mz(pose.eye);
      fit.setTarget(mz(pose.target));
      fit.getViewMatrix(true);
      fit.getProjectionMatrix(true);                      // getTransformationMatrix multiplies the cached projection
      sm.resetRefreshCounter();                           // the maps are drawn again, for this pose, by the next scene.render
      scene.render();
      rtt.render();
      const px = await rtt.readPixels(0, 0, null, true, false);
      const buf = new Float32Array(px.buffer, px.byteOffset, w * h * 4);
      const factor = new Float32Array(w * h);
      for (let i = 0; i < w * h; i++) factor[i] = buf[4 * i];
      const matrices = [];
      for (let i = 0; i < csm.numCascades; i++) {
        const m = Array.from(csm.getCascadeTransformMatrix(i).m);
        for (let j = 8; j < 12; j++) m[j] = -m[j];
        matrices.push(m);
      }
      path.push({ shadow: encode(factor), matrices, clip: true });
    }
  }
  const gl = engine._gl;
  const dbg = gl.getExtension("WEBGL_debug_renderer_info");
  const used = {};
  for (const k of GEN_KEYS) if (!single || k in csm) used[k] = csm[k];
  used.mapSize = mapSize; used.filter = csm.filter; used.backFaceCulling = materials[0].backFaceCulling;
  const res = { engine: "babylon", revision: Engine.Version, width: w, height: h, frame, ...out, cascades, used, ms, maps, path,
                renderer: dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER) };
  engine.dispose();
  return res;
};
