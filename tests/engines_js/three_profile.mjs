// Runs three.js's own CSM addon and DirectionalLight (from the pinned `three` package) in node for
// the toolkit's three.js profile (aliasing/setups/threejs.py) and prints, as JSON on stdout:
//   defaults: the engine's own default objects' values for the profile's setting keys
//             (new CSM({camera, parent}), its lights' shadow, new DirectionalLight().shadow, a new
//             material, the WebGL renderer's shadow map), and THREE's constants by name;
//   cases:    per case and light direction, each cascade's texel: its shadow camera's extent ÷ map size.
//
// usage: node three_profile.mjs PACKAGE_ROOT JSON
//   JSON {"lights": [[x, y, z], ...] (towards the light, toolkit eye frame: x right, y up, z along the view),
//         "cases": [{"near", "far", "fov" (vertical, deg), "aspect", "settings": {profile keys: values}}, ...]}
// A case's settings use the profile's keys: the CSM constructor's data (cascades, maxFar, mode,
// shadowMapSize, shadowBias, lightNear, lightFar, lightMargin), fade (set after construction, as
// the addon requires), customSplitsLambda (with mode 'custom': a customSplitsCallback lerping
// uniform and logarithmic breaks), class 'DirectionalLight' with shadow.camera.* and shadow.mapSize.width.
import { pathToFileURL } from "node:url";
import path from "node:path";

const [root, text] = process.argv.slice(2);
const args = JSON.parse(text);
const load = (p) => import(pathToFileURL(path.join(root, "node_modules", "three", p)).href);
const THREE = await load("build/three.module.js");
const { CSM } = await load("examples/jsm/csm/CSM.js");
const { WebGLShadowMap } = await load("src/renderers/webgl/WebGLShadowMap.js");

function makeCamera(c) {
  const camera = new THREE.PerspectiveCamera(c.fov, c.aspect, c.near, c.far);
  camera.rotation.set(Math.PI / 2, 0, 0); // three's view direction -z turns to world +y
  camera.updateMatrixWorld(true);
  return camera;
}

function defaults() {
  const camera = makeCamera({ fov: 50, aspect: 16 / 9, near: 0.1, far: 500 });
  const csm = new CSM({ camera, parent: new THREE.Object3D() });
  const light = new THREE.DirectionalLight();
  const material = new THREE.MeshStandardMaterial();
  const shadowMap = new WebGLShadowMap({}, {}, { maxTextureSize: 16384 });
  const s = light.shadow;
  const values = {
    cascades: csm.cascades, maxFar: csm.maxFar, mode: csm.mode, shadowMapSize: csm.shadowMapSize, shadowBias: csm.shadowBias,
    lightNear: csm.lightNear, lightFar: csm.lightFar, lightMargin: csm.lightMargin, fade: csm.fade,
    "shadow.bias": s.bias, "shadow.normalBias": s.normalBias, "shadow.radius": s.radius, "shadow.blurSamples": s.blurSamples,
    "shadow.mapSize.width": s.mapSize.width, "shadow.camera.left": s.camera.left, "shadow.camera.right": s.camera.right,
    "shadow.camera.top": s.camera.top, "shadow.camera.bottom": s.camera.bottom, "shadow.camera.near": s.camera.near,
    "shadow.camera.far": s.camera.far, "material.side": material.side, "material.shadowSide": material.shadowSide,
    "renderer.shadowMap.type": shadowMap.type,
  };
  // CSM hands its shadowBias and shadowMapSize to every cascade light, and keeps their other shadow defaults
  const csmLight = csm.lights[0].shadow;
  const handed = { bias: csmLight.bias, mapSize: csmLight.mapSize.width, near: csmLight.camera.near, far: csmLight.camera.far,
                   normalBias: csmLight.normalBias, radius: csmLight.radius };
  const names = ["FrontSide", "BackSide", "DoubleSide", "BasicShadowMap", "PCFShadowMap", "PCFSoftShadowMap", "VSMShadowMap"];
  csm.remove();
  return { values, handed, constants: Object.fromEntries(names.map((n) => [n, THREE[n]])) };
}

function run(c) {
  const camera = makeCamera(c);
  const st = c.settings;
  const rows = [];
  for (const l of args.lights) {
    const shine = new THREE.Vector3(-l[0], -l[1], l[2]).transformDirection(camera.matrixWorld); // along -L, in world
    if (st.class === "DirectionalLight") {
      const light = new THREE.DirectionalLight();
      for (const side of ["left", "right", "top", "bottom", "near", "far"]) {
        if (`shadow.camera.${side}` in st) light.shadow.camera[side] = st[`shadow.camera.${side}`];
      }
      if ("shadow.mapSize.width" in st) light.shadow.mapSize.set(st["shadow.mapSize.width"], st["shadow.mapSize.width"]);
      const cam = light.shadow.camera;
      rows.push({ texels: [[(cam.right - cam.left) / light.shadow.mapSize.width, (cam.top - cam.bottom) / light.shadow.mapSize.height]],
                  depth: [cam.far - cam.near] });
      continue;
    }
    const data = { camera, parent: new THREE.Object3D(), lightDirection: shine };
    for (const k of ["cascades", "maxFar", "mode", "shadowMapSize", "shadowBias", "lightNear", "lightFar", "lightMargin"]) {
      if (k in st) data[k] = st[k];
    }
    if (st.mode === "custom") {
      const lam = st.customSplitsLambda ?? 0.5;
      data.customSplitsCallback = (n, near, far, breaks) => {
        for (let i = 1; i < n; i++) breaks.push(THREE.MathUtils.lerp((near + (far - near) * i / n) / far, near * (far / near) ** (i / n) / far, lam));
        breaks.push(1);
      };
    }
    const csm = new CSM(data);
    if (st.fade) {
      csm.fade = true; // the constructor ignores data.fade
      csm.updateFrustums();
    }
    csm.update();
    rows.push({
      texels: csm.lights.map((light) => {
        const cam = light.shadow.camera;
        return [(cam.right - cam.left) / light.shadow.mapSize.width, (cam.top - cam.bottom) / light.shadow.mapSize.height];
      }),
      depth: csm.lights.map((light) => light.shadow.camera.far - light.shadow.camera.near),
    });
    csm.remove();
  }
  return { rows };
}

process.stdout.write(JSON.stringify({ revision: THREE.REVISION, defaults: defaults(), cases: args.cases.map(run) }) + "\n");
