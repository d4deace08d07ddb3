// Helpers shared by the engine pages: the job's arrays in and the read-back arrays out (base64).

export function decodeF32(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

export function encode(typed) {
  const bytes = new Uint8Array(typed.buffer, typed.byteOffset, typed.byteLength);
  let out = "";
  const step = 0x8000;
  for (let i = 0; i < bytes.length; i += step) out += String.fromCharCode.apply(null, bytes.subarray(i, i + step));
  return btoa(out);
}

// per-triangle flat normals of a triangle soup (T*9 floats): the geometric normal of each corner's triangle
export function flatNormals(pos) {
  const n = new Float32Array(pos.length);
  for (let t = 0; t < pos.length; t += 9) {
    const ax = pos[t + 3] - pos[t], ay = pos[t + 4] - pos[t + 1], az = pos[t + 5] - pos[t + 2];
    const bx = pos[t + 6] - pos[t], by = pos[t + 7] - pos[t + 1], bz = pos[t + 8] - pos[t + 2];
    let x = ay * bz - az * by, y = az * bx - ax * bz, z = ax * by - ay * bx;
    const l = Math.hypot(x, y, z) || 1;
    x /= l; y /= l; z /= l;
    for (let k = 0; k < 3; k++) { n[t + 3 * k] = x; n[t + 3 * k + 1] = y; n[t + 3 * k + 2] = z; }
  }
  return n;
}

// An engine's shadow map, read back: WebGL 2 cannot readPixels a depth texture, so a small pass
// draws each texel's stored depth (texelFetch of the map's own depth texture, every `stride`-th
// texel in s and t) into an RGBA32F colour target and reads that.  The depth texture's compare mode
// and filters are set to NONE/NEAREST for the pass (a compare-mode depth texture is undefined
// through a plain sampler) and put back after it; the caller resets the engine's cached GL state.
// `layers` null: a TEXTURE_2D; otherwise a TEXTURE_2D_ARRAY with that many layers.
// Returns per layer (or the one map) a base64 Float32Array of (size/stride)² depths, rows by t
// upward (row j holds t index j·stride), as the map's own texel rows.
export function readDepthTexture(gl, texture, size, stride, layers) {
  const array = layers !== null && layers !== undefined;
  const target = array ? gl.TEXTURE_2D_ARRAY : gl.TEXTURE_2D;
  const n = Math.floor(size / stride);
  const vs = "#version 300 es\nvoid main(){vec2 p=vec2(float((gl_VertexID<<1)&2),float(gl_VertexID&2));gl_Position=vec4(p*2.0-1.0,0.0,1.0);}";
  const fs = "#version 300 es\nprecision highp float;precision highp int;\n" +
    (array ? "uniform highp sampler2DArray d;" : "uniform highp sampler2D d;") +
    "uniform int layer;uniform int stride;out vec4 o;void main(){ivec2 ij=ivec2(gl_FragCoord.xy)*stride;" +
    (array ? "o=vec4(texelFetch(d,ivec3(ij,layer),0).r,0.0,0.0,1.0);}" : "o=vec4(texelFetch(d,ij,0).r,0.0,0.0,1.0);}");
  const shader = (type, src) => {
    const s = gl.createShader(type);
    gl.shaderSource(s, src); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("depth read-back shader: " + gl.getShaderInfoLog(s));
    return s;
  };
  const prog = gl.createProgram();
  gl.attachShader(prog, shader(gl.VERTEX_SHADER, vs)); gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, fs));
  gl.linkProgram(prog);
  if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error("depth read-back program: " + gl.getProgramInfoLog(prog));
  const color = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(gl.TEXTURE_2D, color);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, n, n);
  const fb = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, color, 0);
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error("depth read-back: float colour target incomplete");
  gl.bindTexture(target, texture);
  const saved = [gl.TEXTURE_COMPARE_MODE, gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER].map((p) => [p, gl.getTexParameter(target, p)]);
  gl.texParameteri(target, gl.TEXTURE_COMPARE_MODE, gl.NONE);
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  gl.bindSampler(0, null);
  gl.useProgram(prog);
  gl.bindVertexArray(null);
  gl.disable(gl.DEPTH_TEST); gl.disable(gl.BLEND); gl.disable(gl.CULL_FACE); gl.disable(gl.SCISSOR_TEST); gl.disable(gl.STENCIL_TEST);
  gl.colorMask(true, true, true, true);
  gl.viewport(0, 0, n, n);
  gl.uniform1i(gl.getUniformLocation(prog, "d"), 0);
  gl.uniform1i(gl.getUniformLocation(prog, "stride"), stride);
  const out = [];
  const buf = new Float32Array(n * n * 4);
  for (let l = 0; l < (array ? layers : 1); l++) {
    gl.uniform1i(gl.getUniformLocation(prog, "layer"), l);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.readPixels(0, 0, n, n, gl.RGBA, gl.FLOAT, buf);
    const d = new Float32Array(n * n);
    for (let i = 0; i < n * n; i++) d[i] = buf[4 * i];
    out.push(encode(d));
  }
  for (const [p, v] of saved) gl.texParameteri(target, p, v);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteFramebuffer(fb); gl.deleteTexture(color); gl.deleteProgram(prog);
  return { maps: out, side: n, stride };
}
