// The WebGL pixel local storage test's page script: for each case (a layout's include, shaders
// a user would write around it, and input texels), two draws in one pixel local storage pass
// through the generated host module, then the planes and the decoded fields read back. The
// results go into <pre id="results"> as JSON, which the Rust test reads from Chromium's DOM.
//
// Pixel (x, y) of the pass belongs to texel (y * texelsPerRow + floor(x / columns)); its
// `columns` pixels each write four of the texel's `outputs` scalars to the colour output.

const VERTEX = `#version 300 es
void main() {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
`;

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    throw new Error(`compile: ${gl.getShaderInfoLog(shader)}`);
  }
  return shader;
}

function program(gl, fragment) {
  const made = gl.createProgram();
  gl.attachShader(made, compile(gl, gl.VERTEX_SHADER, VERTEX));
  gl.attachShader(made, compile(gl, gl.FRAGMENT_SHADER, fragment));
  gl.linkProgram(made);
  if (!gl.getProgramParameter(made, gl.LINK_STATUS)) {
    throw new Error(`link: ${gl.getProgramInfoLog(made)}`);
  }
  return made;
}

function uintTexture(gl, width, height, data) {
  const texture = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, texture);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R32UI, width, height);
  gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RED_INTEGER, gl.UNSIGNED_INT, data);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  return texture;
}

// The first component of every pixel of `texture` (R32UI or RGBA32UI: integers; RGBA8: the
// four bytes as one little-endian word).
function readTexture(gl, texture, internalFormat, width, height, components) {
  const framebuffer = gl.createFramebuffer();
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, framebuffer);
  gl.framebufferTexture2D(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
  let pixels;
  if (internalFormat === "RGBA8") {
    const bytes = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
    pixels = Array.from(new Uint32Array(bytes.buffer));
  } else {
    const words = new Uint32Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA_INTEGER, gl.UNSIGNED_INT, words);
    pixels = [];
    for (let pixel = 0; pixel < width * height; pixel += 1) {
      for (let component = 0; component < components; component += 1) {
        pixels.push(words[pixel * 4 + component]);
      }
    }
  }
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  gl.deleteFramebuffer(framebuffer);
  return pixels;
}

function runCase(gl, host, test) {
  const { width, height, columns, scalars, outputs } = test;
  const pls = host.enablePixelLocalStorage(gl, 1);
  const store = program(gl, test.store);
  const reload = program(gl, test.reload);
  const texelsPerRow = width / columns;
  const inputs = uintTexture(gl, texelsPerRow * scalars, height, new Uint32Array(test.inputs));

  const planes = host.createPlaneTextures(gl, width, height);
  const decoded = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, decoded);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32UI, width, height);
  const framebuffer = gl.createFramebuffer();
  gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, framebuffer);
  gl.framebufferTexture2D(gl.DRAW_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, decoded, 0);
  gl.drawBuffers([gl.COLOR_ATTACHMENT0]);
  host.attachPlanes(gl, pls, planes);
  gl.viewport(0, 0, width, height);

  host.beginPixelLocalStorage(gl, pls, "zero");
  gl.useProgram(store);
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(gl.TEXTURE_2D, inputs);
  gl.uniform1i(gl.getUniformLocation(store, "harness_inputs"), 0);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  host.pixelLocalStorageBarrier(pls);
  gl.useProgram(reload);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  host.endPixelLocalStorage(gl, pls, true);
  gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
  const error = gl.getError();
  if (error !== gl.NO_ERROR) {
    throw new Error(`GL error ${error} during the pass`);
  }

  // Per texel: its words (one pixel of each plane) and its decoded scalars (its pixels of the
  // colour output, four scalars each).
  const planeWords = host.PLANES.map((plane, index) =>
    readTexture(gl, planes[index], plane.internalFormat, width, height, 1),
  );
  const decodedScalars = readTexture(gl, decoded, "RGBA32UI", width, height, 4);
  const words = [];
  const scalarsOut = [];
  for (let texel = 0; texel < texelsPerRow * height; texel += 1) {
    const y = Math.floor(texel / texelsPerRow);
    const x = (texel % texelsPerRow) * columns;
    const pixel = y * width + x;
    for (const plane of planeWords) {
      words.push(plane[pixel]);
    }
    scalarsOut.push(...decodedScalars.slice(pixel * 4, pixel * 4 + outputs));
  }
  return { words, decoded: scalarsOut, coherent: pls.isCoherent() };
}

export function run(cases) {
  const results = [];
  const canvas = document.createElement("canvas");
  const gl = canvas.getContext("webgl2");
  const renderer = gl
    ? gl.getParameter(gl.getExtension("WEBGL_debug_renderer_info")?.UNMASKED_RENDERER_WEBGL ?? gl.RENDERER)
    : "no WebGL 2";
  for (const [host, test] of cases) {
    try {
      results.push({ name: test.name, ...runCase(gl, host, test) });
    } catch (error) {
      results.push({ name: test.name, error: String(error && error.message ? error.message : error) });
    }
  }
  document.getElementById("results").textContent = JSON.stringify({ renderer, results });
}
