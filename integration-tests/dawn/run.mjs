// Compiles WGSL with Chrome's compiler, Tint, through Dawn's Node bindings (npm `webgpu`),
// found in the folder $GBUFFER_DAWN_MODULES (a node_modules folder; .ci/run installs it).
//
// Usage: node run.mjs JOBS.json RESULTS.json
//
// JOBS.json is a list of {name, wgsl}. Every job's WGSL becomes a shader module, and the
// messages Tint gives (errors, warnings, infos) are reported: RESULTS.json gets one {name,
// messages, error} per job, the adapter's description and whether it has shader-f16.
//
// The adapter: Dawn's Vulkan backend where the driver serves it (core WebGPU), else its OpenGL
// ES backend in compatibility mode (Mesa 22.3's lavapipe lacks a feature Dawn's Vulkan needs;
// its llvmpipe runs GLES 3.2 without a display through EGL_PLATFORM=surfaceless).

import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [jobsPath, resultsPath] = process.argv.slice(2);
const modules = process.env.GBUFFER_DAWN_MODULES;
const { create, globals } = await import(pathToFileURL(join(modules, 'webgpu', 'index.js')));
Object.assign(globalThis, globals);

async function adapter() {
  const tries = [
    [['backend=vulkan'], 'core'],
    [['backend=opengles'], 'compatibility'],
  ];
  for (const [flags, featureLevel] of tries) {
    const found = await create(flags).requestAdapter({ featureLevel });
    if (found) {
      return { found, description: `${found.info.description} (${flags[0]}, ${featureLevel})` };
    }
  }
  throw new Error('Dawn found no adapter on its Vulkan or OpenGL ES backend');
}

const { found, description } = await adapter();
const features = found.features.has('shader-f16') ? ['shader-f16'] : [];
const device = await found.requestDevice({ requiredFeatures: features });
const jobs = JSON.parse(readFileSync(jobsPath, 'utf8'));
const results = [];
for (const job of jobs) {
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code: job.wgsl });
  const info = await module.getCompilationInfo();
  const messages = info.messages.map((message) => ({
    type: message.type,
    text: message.message,
    line: message.lineNum,
  }));
  const scope = await device.popErrorScope();
  results.push({ name: job.name, messages, error: scope ? scope.message : null });
}
writeFileSync(resultsPath, JSON.stringify({ adapter: description, f16: features.length > 0, results }));
process.exit(0);
