// The reference scene's deferred frame in one WebGL 2 pixel local storage pass: the mesh
// writes the G-buffer into the planes, four decals repaint it in place, a fullscreen draw puts
// the environment's, the sun's and the 32 point lights' light into its light accumulation,
// and the resolve tone-maps it (the sky where there is no surface) into the one colour target.
// The planes start at zero on tile and are never stored: on a tiler the G-buffer costs no
// bandwidth at all. The same draws, in the same order and depth states, as the GLES renderer's
// fused paths (render/src/gles/mod.rs).
//
// `host` is the layout's generated module (<layout>.webgl_pls.js); `scene` the renderer's export
// (scene.mjs: the programs, the mesh, the baked inputs).

function bytes(base64) {
  const text = atob(base64);
  const out = new Uint8Array(text.length);
  for (let index = 0; index < text.length; index += 1) {
    out[index] = text.charCodeAt(index);
  }
  return out;
}

function compile(gl, type, source, what) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    throw new Error(`${what}: ${gl.getShaderInfoLog(shader)}`);
  }
  return shader;
}

function link(gl, program) {
  const made = gl.createProgram();
  gl.attachShader(made, compile(gl, gl.VERTEX_SHADER, program.vertex, `${program.stage} vertex`));
  gl.attachShader(made, compile(gl, gl.FRAGMENT_SHADER, program.fragment, `${program.stage} fragment`));
  gl.linkProgram(made);
  if (!gl.getProgramParameter(made, gl.LINK_STATUS)) {
    throw new Error(`${program.stage}: ${gl.getProgramInfoLog(made)}`);
  }
  gl.useProgram(made);
  for (const [name, unit] of program.samplers) {
    gl.uniform1i(gl.getUniformLocation(made, name), unit);
  }
  return made;
}

// The inputs, each on its unit, sampled as wgpu samples them: trilinear, the environment
// wrapping around the sky in s, everything else clamped to its edges.
function upload(gl, textures) {
  for (const texture of textures) {
    const made = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + texture.unit);
    gl.bindTexture(gl.TEXTURE_2D, made);
    const [first] = texture.mips;
    gl.texStorage2D(gl.TEXTURE_2D, texture.mips.length, gl[texture.internalFormat], first.width, first.height);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    texture.mips.forEach((mip, level) => {
      const data = bytes(mip.bytes);
      const [type, view] =
        texture.internalFormat === "RGBA16F"
          ? [gl.HALF_FLOAT, new Uint16Array(data.buffer)]
          : [gl.UNSIGNED_BYTE, data];
      gl.texSubImage2D(gl.TEXTURE_2D, level, 0, 0, mip.width, mip.height, gl.RGBA, type, view);
    });
    const sampler = gl.createSampler();
    gl.samplerParameteri(sampler, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
    gl.samplerParameteri(sampler, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.samplerParameteri(sampler, gl.TEXTURE_WRAP_S, texture.repeat ? gl.REPEAT : gl.CLAMP_TO_EDGE);
    gl.samplerParameteri(sampler, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.bindSampler(texture.unit, sampler);
  }
  gl.activeTexture(gl.TEXTURE0);
}

// The mesh (position, normal, object) and the volumes' instance index (a buffer of 0, 1, 2, ...
// whose offset picks the volume drawn: WebGL 2 has no base instance).
function geometry(gl, scene) {
  const mesh = gl.createVertexArray();
  gl.bindVertexArray(mesh);
  gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
  gl.bufferData(gl.ARRAY_BUFFER, bytes(scene.MESH.vertices), gl.STATIC_DRAW);
  gl.enableVertexAttribArray(0);
  gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 28, 0);
  gl.enableVertexAttribArray(1);
  gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 28, 12);
  gl.enableVertexAttribArray(2);
  gl.vertexAttribIPointer(2, 1, gl.UNSIGNED_INT, 28, 24);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, gl.createBuffer());
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, bytes(scene.MESH.indices), gl.STATIC_DRAW);
  const volumes = gl.createVertexArray();
  gl.bindVertexArray(volumes);
  const count = scene.POINT_LIGHT_COUNT + scene.DECAL_COUNT;
  const indexBuffer = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, indexBuffer);
  gl.bufferData(gl.ARRAY_BUFFER, new Uint32Array([...Array(count).keys()]), gl.STATIC_DRAW);
  gl.enableVertexAttribArray(0);
  gl.vertexAttribDivisor(0, 1);
  gl.bindVertexArray(null);
  return { mesh, volumes, indexBuffer };
}

/**
 * Renders the frame and returns its pixels, RGBA8, the image's top row first (the scene's clip
 * space is flipped in y, so GL's first row is the image's top), and the calls that decide what
 * the frame moves to and from memory: the pass's attachments and planes with how each starts
 * (`clear` or `load`), the draws, what is invalidated, and what the pass stores (as
 * gbuffer_render::recording records the other backends' frames).
 */
export function renderFrame(gl, host, scene) {
  const pls = host.enablePixelLocalStorage(gl, 1);
  // Each stage's program, and where its `volume_index` uniform is (null where it has none).
  const programs = new Map(
    scene.PROGRAMS.map((source) => {
      const program = link(gl, source);
      return [source.stage, { program, volumeIndex: gl.getUniformLocation(program, "volume_index") }];
    }),
  );
  upload(gl, scene.TEXTURES);
  const { mesh, volumes, indexBuffer } = geometry(gl, scene);
  const [width, height] = [scene.WIDTH, scene.HEIGHT];

  const output = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, output);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA8, width, height);
  const depth = gl.createRenderbuffer();
  gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
  gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, width, height);
  const framebuffer = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, output, 0);
  gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
  host.attachPlanes(gl, pls, host.createPlaneTextures(gl, width, height));
  gl.viewport(0, 0, width, height);
  gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]);
  gl.clearBufferfv(gl.DEPTH, 0, [1]);

  const calls = [];
  const draw = (stage, how, volume) => {
    const { program, volumeIndex } = programs.get(stage);
    calls.push({ draw: stage });
    gl.useProgram(program);
    // Only the resolve and the sky write the output; the other draws change the planes alone.
    const output = stage === "resolve" || stage === "sky";
    gl.colorMask(output, output, output, output);
    if (how === "mesh") {
      gl.bindVertexArray(mesh);
      gl.drawElements(gl.TRIANGLES, scene.MESH.indexCount, gl.UNSIGNED_INT, 0);
    } else if (how === "fullscreen") {
      gl.bindVertexArray(null);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    } else {
      gl.bindVertexArray(volumes);
      gl.bindBuffer(gl.ARRAY_BUFFER, indexBuffer);
      gl.vertexAttribIPointer(0, 1, gl.UNSIGNED_INT, 4, 4 * volume);
      gl.uniform1ui(volumeIndex, volume);
      gl.drawArraysInstanced(gl.TRIANGLES, 0, 6, 1);
    }
    // Each draw reads what the last one wrote at the same pixel.
    host.pixelLocalStorageBarrier(pls);
  };

  gl.enable(gl.DEPTH_TEST);
  host.beginPixelLocalStorage(gl, pls, "zero");
  // Every plane starts at zero and the output and depth cleared: nothing is loaded.
  calls.push({
    beginPass: [
      ...host.PLANES.map((plane) => [plane.name, 4, "clear"]),
      ["output", 4, "clear"],
      ["depth", 4, "clear"],
    ],
  });
  gl.depthMask(true);
  gl.depthFunc(gl.LESS);
  draw("geometry", "mesh");
  // Everything after the geometry is drawn over the surfaces only (GREATER than their depth)
  // or over the sky only (EQUAL to the cleared far plane).
  gl.depthMask(false);
  gl.depthFunc(gl.GREATER);
  for (let decal = 0; decal < scene.DECAL_COUNT; decal += 1) {
    draw("decal", "volume", scene.POINT_LIGHT_COUNT + decal);
  }
  draw("lighting", "fullscreen");
  draw("resolve", "fullscreen");
  gl.depthFunc(gl.EQUAL);
  draw("sky", "fullscreen");
  // The planes die here, never stored, and depth with them.
  host.endPixelLocalStorage(gl, pls, false);
  gl.invalidateFramebuffer(gl.FRAMEBUFFER, [gl.DEPTH_ATTACHMENT]);
  calls.push({ invalidate: [...host.PLANES.map((plane) => plane.name), "depth"] });
  calls.push({ endPass: ["output"] });
  const error = gl.getError();
  if (error !== gl.NO_ERROR) {
    throw new Error(`GL error ${error} while drawing the frame`);
  }
  const pixels = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  calls.push({ readBack: "output" });
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  return { pixels, calls };
}
