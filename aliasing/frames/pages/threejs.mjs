// three.js's own frame: WebGLRenderer with the CSM addon (examples/jsm/csm), read back per pixel.
//
// window.frame(job) renders the job's scene (a triangle soup in a right-handed, y-up world) with
// the job's camera and sun, and returns what the engine computed:
//   shadow    per pixel: the raw shadow factor that three.js multiplies into the light (the
//             value getShadow returned for the cascade CSM picked), the cascade index, n·l
//   position  per pixel: world position (x, y, z, 1; w = 0 where nothing is drawn)
//   normal    per pixel: world normal of the drawn face, turned towards the eye
//   cascades  per cascade: the shadow matrix (world -> [0,1]^3, column-major), map size, bias
// The shadow factor is captured by rewriting, in ShaderChunk.lights_fragment_begin, each
// `directLight.color *= (...) ? getShadow( directionalShadowMap[ i ], ... ) : 1.0;` into a block
// that also stores the factor; nothing else of the lighting is changed.
import * as THREE from "three";
import { CSM } from "three/addons/csm/CSM.js";
import { decodeF32, encode, flatNormals, readDepthTexture } from "./common.mjs";

const SIDES = { front: THREE.FrontSide, back: THREE.BackSide, double: THREE.DoubleSide };
const MAP_TYPES = { BasicShadowMap: THREE.BasicShadowMap, PCFShadowMap: THREE.PCFShadowMap, PCFSoftShadowMap: THREE.PCFSoftShadowMap, VSMShadowMap: THREE.VSMShadowMap };
const CAPTURE = /directLight\.color \*= (\( directLight\.visible && receiveShadow \) \? getShadow\( directionalShadowMap\[ i \],[^;]*?: 1\.0);/g;

function instrument() {
  const chunk = THREE.ShaderChunk.lights_fragment_begin;
  if (chunk.includes("frShadow")) return;
  const n = (chunk.match(CAPTURE) || []).length;
  if (n === 0) throw new Error("three.js lights_fragment_begin: no directional getShadow call found to capture");
  THREE.ShaderChunk.lights_fragment_begin = "float frShadow = 1.0; float frCascade = -1.0;\n" +
    chunk.replace(CAPTURE, "{ float frS = $1; frShadow = frS; frCascade = float( UNROLLED_LOOP_INDEX ); directLight.color *= frS; }");
}

function material(mode, side, shadowSide, csm) {
  const m = new THREE.MeshLambertMaterial({ color: 0xffffff, side });
  m.shadowSide = shadowSide;
  if (csm) csm.setupMaterial(m);
  const engineHook = m.onBeforeCompile;
  m.onBeforeCompile = (shader, renderer) => {
    if (engineHook) engineHook.call(m, shader, renderer);
    shader.vertexShader = shader.vertexShader
      .replace("void main() {", "varying vec3 vFrWorld;\nvarying vec3 vFrNormal;\nvoid main() {")
      .replace("#include <project_vertex>", "#include <project_vertex>\nvFrWorld = ( modelMatrix * vec4( transformed, 1.0 ) ).xyz;\nvFrNormal = normalize( mat3( modelMatrix ) * objectNormal );");
    const out = mode === 1 ? "gl_FragColor = vec4( frShadow, frCascade, saturate( dot( geometryNormal, directLight.direction ) ), 1.0 );"
      : mode === 2 ? "gl_FragColor = vec4( vFrWorld, 1.0 );"
      : mode === 3 ? "gl_FragColor = vec4( gl_FrontFacing ? vFrNormal : - vFrNormal, 1.0 );" : "";
    shader.fragmentShader = shader.fragmentShader
      .replace("void main() {", "varying vec3 vFrWorld;\nvarying vec3 vFrNormal;\nvoid main() {")
      .replace("#include <dithering_fragment>", "#include <dithering_fragment>\n" + out);
  };
  m.customProgramCacheKey = () => `frames-${mode}`;
  return m;
}

function readTarget(renderer, scene, camera, target, w, h) {
  renderer.setRenderTarget(target);
  renderer.setClearColor(0x000000, 0);
  renderer.clear();
  renderer.render(scene, camera);
  const buf = new Float32Array(w * h * 4);
  renderer.readRenderTargetPixels(target, 0, 0, w, h, buf);
  renderer.setRenderTarget(null);
  return buf;
}

window.frame = async (job) => {
  const w = job.width, h = job.height, s = job.settings;
  const canvas = document.createElement("canvas");
  canvas.width = w; canvas.height = h;
  document.body.appendChild(canvas);
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
  if (!renderer.getContext() || !(renderer.getContext() instanceof WebGL2RenderingContext)) throw new Error("no WebGL 2 context");
  if (!renderer.extensions.has("EXT_color_buffer_float")) throw new Error("WebGL 2 without EXT_color_buffer_float: float read-back impossible");
  renderer.setPixelRatio(1);
  renderer.setSize(w, h, false);
  renderer.shadowMap.enabled = true;
  if (s.shadowMapType !== undefined) {
    if (!(s.shadowMapType in MAP_TYPES)) throw new Error(`shadowMapType must be one of ${Object.keys(MAP_TYPES).join(", ")}`);
    renderer.shadowMap.type = MAP_TYPES[s.shadowMapType];
  }

  const c = job.camera;
  const camera = new THREE.PerspectiveCamera(c.fov, w / h, c.near, c.far);
  camera.position.set(...c.eye);
  camera.up.set(...c.up);
  camera.lookAt(new THREE.Vector3(...c.target));
  camera.updateMatrixWorld(true);

  const scene = new THREE.Scene();
  const shine = new THREE.Vector3(-job.sun[0], -job.sun[1], -job.sun[2]).normalize(); // along the light
  let csm = null, lights;
  if (s.class === "DirectionalLight") {
    // one DirectionalLight: its shadow camera is the orthographic box the user sets, placed at
    // the light and looking at its target (LightShadow.updateMatrices); the page puts the target
    // at job.lightTarget and the light (near + far)/2 from it towards the sun
    const light = new THREE.DirectionalLight(0xffffff, 3);
    const t = new THREE.Vector3(...job.lightTarget);
    light.target.position.copy(t);
    light.position.copy(t).addScaledVector(shine, -(s.near + s.far) / 2);
    light.castShadow = true;
    const cam = light.shadow.camera;
    Object.assign(cam, { left: s.left, right: s.right, top: s.top, bottom: s.bottom, near: s.near, far: s.far });
    cam.updateProjectionMatrix();
    light.shadow.mapSize.set(s.mapSize, s.mapSize);
    light.shadow.bias = s.bias;
    light.shadow.normalBias = s.normalBias;
    light.shadow.radius = s.radius;
    scene.add(light, light.target);
    lights = [light];
  } else {
    const data = { camera, parent: scene, lightDirection: shine };
    for (const k of ["cascades", "maxFar", "mode", "shadowMapSize", "shadowBias", "lightIntensity", "lightNear", "lightFar", "lightMargin", "fade"]) {
      if (s[k] !== undefined && k !== "fade") data[k] = s[k];
    }
    csm = new CSM(data);
    if (s.fade !== undefined) csm.fade = s.fade;
    for (const light of csm.lights) {
      if (s.normalBias !== undefined) light.shadow.normalBias = s.normalBias;
      if (s.bias !== undefined) light.shadow.bias = s.bias;
      if (s.shadowRadius !== undefined) light.shadow.radius = s.shadowRadius;
    }
    lights = csm.lights;
  }
  instrument();
  scene.add(new THREE.AmbientLight(0xffffff, 0.25));

  const pos = decodeF32(job.triangles);
  const geo = new THREE.BufferGeometry();
  geo.setAttribute("position", new THREE.BufferAttribute(pos, 3));
  geo.setAttribute("normal", new THREE.BufferAttribute(flatNormals(pos), 3));
  const side = SIDES[s.side ?? "front"];
  const shadowSide = s.shadowSide === null || s.shadowSide === undefined ? null : SIDES[s.shadowSide];
  if (side === undefined || shadowSide === undefined) throw new Error("side and shadowSide must be front, back, double (shadowSide also null)");
  const materials = [0, 1, 2, 3].map((mode) => material(mode, side, shadowSide, csm));
  const mesh = new THREE.Mesh(geo, materials[0]);
  mesh.castShadow = true; mesh.receiveShadow = true;
  mesh.frustumCulled = false;
  scene.add(mesh);

  if (csm) csm.update();
  else scene.updateMatrixWorld(true);
  const t0 = performance.now();
  renderer.render(scene, camera);                       // the engine's own frame (shadow maps drawn here)
  const frame = canvas.toDataURL("image/png");
  const target = new THREE.WebGLRenderTarget(w, h, { type: THREE.FloatType, format: THREE.RGBAFormat, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter });
  renderer.shadowMap.autoUpdate = false;                // the read-back passes reuse the frame's maps
  const gl0 = renderer.getContext();
  const out = {};
  for (const [mode, name] of [[1, "shadow"], [2, "position"], [3, "normal"]]) {
    mesh.material = materials[mode];
    out[name] = encode(readTarget(renderer, scene, camera, target, w, h));
  }
  // the shadow maps as drawn for this frame (job.maps: every stride-th texel, at most job.maps.side per side)
  let maps = null;
  if (job.maps) {
    maps = csm.lights.map((l) => {
      const size = l.shadow.map.width, stride = Math.max(1, Math.ceil(size / job.maps.side));
      const tex = renderer.properties.get(l.shadow.map.depthTexture).__webglTexture;
      const got = readDepthTexture(gl0, tex, size, stride, null);
      return { depth: got.maps[0], side: got.side, stride, size, matrix: [...l.shadow.matrix.elements] };
    });
    renderer.resetState();                              // three.js's cached GL state: the pass above changed it
  }
  // a camera path: the cascades follow a moving camera while the picture's camera stays, so every
  // pixel keeps its world point and a change of its factor is the maps' motion alone
  const path = [];
  if (job.path) {
    if (!csm) throw new Error("a camera path is rendered for the CSM class only");
    const fit = camera.clone();
    csm.camera = fit;
    renderer.shadowMap.autoUpdate = true;
    mesh.material = materials[1];
    for (const pose of job.path) {
      fit.position.set(...pose.eye);
      fit.up.set(...c.up);
      fit.lookAt(new THREE.Vector3(...pose.target));
      fit.updateMatrixWorld(true);
      csm.update();
      const buf = readTarget(renderer, scene, camera, target, w, h);
      const factor = new Float32Array(w * h);
      for (let i = 0; i < w * h; i++) factor[i] = buf[4 * i];
      // the depth pass's own uniforms (WebGLShadowMap.renderObject: modelViewMatrix = shadow camera's
      // matrixWorldInverse × the mesh's matrixWorld, the identity here; projectionMatrix), float64 here
      const got = { shadow: encode(factor), matrices: csm.lights.map((l) => [...l.shadow.matrix.elements]),
                    views: csm.lights.map((l) => [...l.shadow.camera.matrixWorldInverse.elements]),
                    projections: csm.lights.map((l) => [...l.shadow.camera.projectionMatrix.elements]) };
      if (job.maps) {                                   // this pose's maps, as read for the frame above
        got.maps = csm.lights.map((l) => {
          const size = l.shadow.map.width, stride = Math.max(1, Math.ceil(size / job.maps.side));
          const read = readDepthTexture(gl0, renderer.properties.get(l.shadow.map.depthTexture).__webglTexture, size, stride, null);
          return { depth: read.maps[0], side: read.side, stride, size };
        });
        renderer.resetState();
      }
      path.push(got);
    }
  }
  const ms = performance.now() - t0;
  const cascades = lights.map((light) => {
    const sh = light.shadow, cam = sh.camera;
    return { matrix: [...sh.matrix.elements], size: [sh.mapSize.x, sh.mapSize.y], near: cam.near, far: cam.far,
             left: cam.left, right: cam.right, top: cam.top, bottom: cam.bottom, bias: sh.bias, normalBias: sh.normalBias, radius: sh.radius };
  });
  const gl = renderer.getContext();
  const dbg = gl.getExtension("WEBGL_debug_renderer_info");
  return { engine: "threejs", revision: THREE.REVISION, width: w, height: h, frame, ...out, cascades, breaks: csm ? [...csm.breaks] : [], path, maps,
           shadowMapType: renderer.shadowMap.type, ms,
           renderer: dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER) };
};
