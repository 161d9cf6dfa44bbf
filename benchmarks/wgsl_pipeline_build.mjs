#!/usr/bin/env node
// wgsl_pipeline_build.mjs: how long WebGPU (Dawn for Node, the first adapter) takes to build a
// compute pipeline from a WGSL file: createShaderModule, then createComputePipelineAsync, timed
// apart. A measurement for docs/performance.md ("WebGPU on SwiftShader"), not a test.
//
//   node benchmarks/wgsl_pipeline_build.mjs FILE.wgsl ENTRY [ID=VALUE]...
//
// ID=VALUE sets an `override` by its @id (true, false or a number), e.g. 0=false. With no
// adapter (Dawn refuses lavapipe) run it with VK_ICD_FILENAMES=/usr/lib/chromium/vk_swiftshader_icd.json.
import fs from 'node:fs';

const [file, entryPoint, ...assignments] = process.argv.slice(2);
if (!file || !entryPoint) {
  console.error('usage: node benchmarks/wgsl_pipeline_build.mjs FILE.wgsl ENTRY [ID=VALUE]...');
  process.exit(2);
}
const constants = {};
for (const assignment of assignments) {
  const match = /^(\d+)=(true|false|[-+0-9.eE]+)$/.exec(assignment);
  if (!match) {
    console.error(`not ID=VALUE: '${assignment}'`);
    process.exit(2);
  }
  constants[match[1]] = match[2] === 'true' ? 1 : match[2] === 'false' ? 0 : Number(match[2]);
}

const webgpu = await import('webgpu');
Object.assign(globalThis, webgpu.globals);
// Referenced until the end: a collected instance takes its device down.
const instance = webgpu.create([]);
const adapter = await instance.requestAdapter();
if (!adapter) {
  console.error('no WebGPU adapter (Dawn refuses lavapipe): set VK_ICD_FILENAMES to SwiftShader\'s driver');
  process.exit(77);
}
const device = await adapter.requestDevice();
const code = fs.readFileSync(file, 'utf8');
let start = performance.now();
const module = device.createShaderModule({ code });
const messages = (await module.getCompilationInfo()).messages.filter((message) => message.type === 'error');
const moduleMs = performance.now() - start;
if (messages.length > 0) {
  console.error(`${file}: ${messages.map((message) => `${message.lineNum}:${message.linePos}: ${message.message}`).join('; ')}`);
  process.exit(1);
}
start = performance.now();
await device.createComputePipelineAsync({ layout: 'auto', compute: { module, entryPoint, constants } });
const pipelineMs = performance.now() - start;
const info = adapter.info ?? {};
console.log(JSON.stringify({
  file, entryPoint, constants, adapter: [info.vendor, info.architecture, info.description].filter((part) => part).join(' '),
  bytes: code.length, shader_module_ms: Math.round(moduleMs), pipeline_ms: Math.round(pipelineMs),
}));
device.destroy();
process.exit(0);
