// Runs WGSL on Chrome's engine: Dawn's Node bindings (npm `webgpu`), whose compiler is Tint.
// The bindings are looked for in the folder $GBUFFER_DAWN_MODULES (a node_modules folder;
// .ci/run installs them there).
//
// Usage: node run.mjs BACKEND JOBS.json RESULTS.json
//
// BACKEND is `vulkan` (core WebGPU; Tint writes SPIR-V) or `opengles` (compatibility mode;
// Tint writes GLSL ES, run on llvmpipe without a display through EGL_PLATFORM=surfaceless).
//
// JOBS.json is a list of jobs. Every job has a `name` and `wgsl`, which becomes a shader
// module; the messages Tint gives (errors, warnings, infos) are reported. A job that also has
// `entry` is a compute dispatch, with the bindings of gbuffer_gpu::Gpu::run_compute: binding 0
// the u32s of the file `inputs`, bindings 1.. one storage buffer of `outputs[i]` u32s each, the
// binding after them a uniform vec4<u32> of (`count`, 0, 0, 0); `workgroups` workgroups. Each
// output buffer is written, as little-endian u32s, to the file `results[i]`.
//
// RESULTS.json gets {adapter, f16, results: [{name, messages, error}]}; `adapter` is null when
// the backend has no adapter here (the caller decides whether that is a failure).

import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [backend, jobsPath, resultsPath] = process.argv.slice(2);
const featureLevel = { vulkan: 'core', opengles: 'compatibility' }[backend];
if (!featureLevel) {
  console.error(`unknown backend ${backend}: vulkan or opengles`);
  process.exit(2);
}
const modules = process.env.GBUFFER_DAWN_MODULES;
const { create, globals } = await import(pathToFileURL(join(modules, 'webgpu', 'index.js')));
Object.assign(globalThis, globals);

// The instance must outlive every callback: once the garbage collector takes it, Dawn's event
// processing reads freed memory (a segfault in CallbackTaskManager::Flush, which looked like a
// driver crash after a few dozen pipelines).
const gpu = create([`backend=${backend}`]);
const adapter = await gpu.requestAdapter({ featureLevel });
if (!adapter) {
  writeFileSync(resultsPath, JSON.stringify({ adapter: null, f16: false, results: [] }));
  process.exit(0);
}
const features = adapter.features.has('shader-f16') ? ['shader-f16'] : [];
const device = await adapter.requestDevice({
  requiredFeatures: features,
  requiredLimits: {
    maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize,
    maxBufferSize: adapter.limits.maxBufferSize,
  },
});
device.lost.then((info) => {
  console.error(`Dawn lost the device: ${info.message}`);
  process.exit(1);
});

// Runs `work` inside validation, internal and out-of-memory error scopes: its value, and the
// first error's message (a scope's, or what `work` threw) or null.
async function scoped(work) {
  const filters = ['validation', 'internal', 'out-of-memory'];
  for (const filter of filters) device.pushErrorScope(filter);
  let value = null;
  let thrown = null;
  try {
    value = await work();
  } catch (exception) {
    thrown = String(exception);
  }
  const errors = [];
  for (const _ of filters) errors.push(await device.popErrorScope());
  const error = errors.find((found) => found);
  return { value, error: error ? error.message : thrown };
}

// A storage or uniform buffer holding `words`.
function bufferOf(words, usage) {
  const buffer = device.createBuffer({ size: Math.max(words.byteLength, 16), usage, mappedAtCreation: true });
  new Uint32Array(buffer.getMappedRange()).set(words);
  buffer.unmap();
  return buffer;
}

// Dispatches a compute job and writes its outputs to `job.results`.
async function dispatch(job, module) {
  const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: job.entry } });
  const bytes = readFileSync(job.inputs);
  const inputs = new Uint32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  const entries = [{ binding: 0, resource: { buffer: bufferOf(inputs, GPUBufferUsage.STORAGE) } }];
  const outputs = job.outputs.map((length) =>
    device.createBuffer({ size: Math.max(length * 4, 16), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC }));
  outputs.forEach((buffer, index) => entries.push({ binding: index + 1, resource: { buffer } }));
  const count = bufferOf(new Uint32Array([job.count, 0, 0, 0]), GPUBufferUsage.UNIFORM);
  entries.push({ binding: outputs.length + 1, resource: { buffer: count } });
  const group = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries });
  const readbacks = outputs.map((buffer) =>
    device.createBuffer({ size: buffer.size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST }));
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(0, group);
  pass.dispatchWorkgroups(job.workgroups);
  pass.end();
  outputs.forEach((buffer, index) => encoder.copyBufferToBuffer(buffer, 0, readbacks[index], 0, buffer.size));
  device.queue.submit([encoder.finish()]);
  for (const [index, readback] of readbacks.entries()) {
    await readback.mapAsync(GPUMapMode.READ);
    const words = new Uint8Array(readback.getMappedRange(), 0, job.outputs[index] * 4);
    writeFileSync(job.results[index], words);
    readback.unmap();
  }
}

const jobs = JSON.parse(readFileSync(jobsPath, 'utf8'));
const results = [];
for (const job of jobs) {
  const { value: module, error: compileError } = await scoped(async () => device.createShaderModule({ code: job.wgsl }));
  const info = await module.getCompilationInfo();
  const messages = info.messages.map((message) => ({ type: message.type, text: message.message, line: message.lineNum }));
  let error = compileError;
  if (!error && job.entry) {
    ({ error } = await scoped(() => dispatch(job, module)));
  }
  results.push({ name: job.name, messages, error });
}
const description = `${adapter.info.description} (Dawn ${backend}, ${featureLevel})`;
writeFileSync(resultsPath, JSON.stringify({ adapter: description, f16: features.length > 0, results }));
process.exit(0);
