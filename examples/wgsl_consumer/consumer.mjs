#!/usr/bin/env node
// The WGSL consumer (examples/wgsl_consumer): the installed openpbr.wgsl with consumer.wgsl
// after it, run on WebGPU through Dawn for Node (npm `webgpu`) with the installed tables, and
// checked: every sample finite and non-negative, each continuous sample's weight equal to
// eval / pdf at its direction (relative 1e-3, the conformance check's bound for a GPU's max
// error), and the white rough metal's albedo 1 within 0.01 (energy compensation: the C++
// consumer's white furnace check). Exit status 0 when all hold, 1 otherwise, 77 without an
// adapter.
//   node consumer.mjs <openpbr.wgsl> <table dir> <node_modules holding webgpu> [SwiftShader ICD.json]
// With no adapter (Dawn refuses lavapipe), it runs again with VK_ICD_FILENAMES naming the
// given SwiftShader driver when that file exists.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const [libraryFile, tableDirectory, nodeModules, swiftshaderDriver] = process.argv.slice(2);
if (!libraryFile || !tableDirectory || !nodeModules) {
  console.error('usage: node consumer.mjs <openpbr.wgsl> <table dir> <node_modules holding webgpu> [SwiftShader ICD.json]');
  process.exit(2);
}
// 65536 samples: the albedo's standard error is about 1e-3 for this lobe, ten times below the
// 0.01 bound.
const sampleCount = 65536;

// By path: ES modules do not search NODE_PATH.
const webgpu = await import(pathToFileURL(path.join(nodeModules, 'webgpu', 'index.js')).href);
Object.assign(globalThis, webgpu.globals);
const instance = webgpu.create([]);
const adapter = await instance.requestAdapter();
if (!adapter) {
  if (swiftshaderDriver && fs.existsSync(swiftshaderDriver) && !process.env.VK_ICD_FILENAMES) {
    const child = spawnSync(process.execPath, [fileURLToPath(import.meta.url), ...process.argv.slice(2)],
      { stdio: 'inherit', env: { ...process.env, VK_ICD_FILENAMES: swiftshaderDriver } });
    process.exit(child.status ?? 1);
  }
  console.log('wgsl_consumer: skipped: no WebGPU adapter');
  process.exit(77);
}
const device = await adapter.requestDevice();
device.pushErrorScope('validation');
if (!fs.existsSync(libraryFile)) {
  console.error(`wgsl_consumer: ${libraryFile} does not exist (OPENPBR_WGSL_LIBRARY)`);
  process.exit(1);
}
const code = fs.readFileSync(libraryFile, 'utf8') + '\n' +
  fs.readFileSync(path.join(path.dirname(fileURLToPath(import.meta.url)), 'consumer.wgsl'), 'utf8');
const module = device.createShaderModule({ label: 'openpbr.wgsl + consumer.wgsl', code });
const errors = (await module.getCompilationInfo()).messages.filter((message) => message.type === 'error');
if (errors.length > 0) {
  console.error(`wgsl_consumer: ${errors.map((m) => `${m.lineNum}:${m.linePos}: ${m.message}`).join('; ')}`);
  process.exit(1);
}
const pipeline = await device.createComputePipelineAsync({ label: 'consumer', layout: 'auto', compute: { module, entryPoint: 'main' } });
const storage = (label, data) => {
  const buffer = device.createBuffer({ label, size: data.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(buffer, 0, data);
  return buffer;
};
const floats = (file) => {
  const where = path.join(tableDirectory, file);
  if (!fs.existsSync(where)) {
    console.error(`wgsl_consumer: ${where} does not exist (the tables of OPENPBR_TABLE_DIR)`);
    process.exit(1);
  }
  const bytes = fs.readFileSync(where);
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
};
const resultBytes = sampleCount * 4 * 4;
const results = device.createBuffer({ label: 'results', size: resultBytes, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
const readback = device.createBuffer({ label: 'readback', size: resultBytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
const bindGroup = device.createBindGroup({
  label: 'consumer bindings',
  layout: pipeline.getBindGroupLayout(0),
  entries: [
    { binding: 0, resource: { buffer: storage('tables', floats('openpbr_lut.bin')) } },
    { binding: 1, resource: { buffer: storage('fuzz table', floats('openpbr_fuzz_ltc.bin')) } },
    { binding: 3, resource: { buffer: storage('parameters', new Uint32Array([sampleCount, 0, 0, 0])) } },
    { binding: 4, resource: { buffer: results } },
  ],
});
const encoder = device.createCommandEncoder();
const pass = encoder.beginComputePass();
pass.setPipeline(pipeline);
pass.setBindGroup(0, bindGroup);
pass.dispatchWorkgroups(sampleCount / 64);
pass.end();
encoder.copyBufferToBuffer(results, 0, readback, 0, resultBytes);
device.queue.submit([encoder.finish()]);
await readback.mapAsync(GPUMapMode.READ);
const values = new Float32Array(readback.getMappedRange().slice(0));
readback.unmap();
const scopeError = await device.popErrorScope();
if (scopeError) {
  console.error(`wgsl_consumer: WebGPU validation: ${scopeError.message}`);
  process.exit(1);
}

let sum = 0;
let failures = 0;
let worstConsistency = 0;
const SPECULAR = 16; // OPENPBR_LOBE_TYPE_SPECULAR (slang/lobes/openpbr_lobe_common.h): a delta lobe, no eval / pdf
for (let i = 0; i < sampleCount; i++) {
  const [weight, pdf, ratio, lobe] = values.subarray(4 * i, 4 * i + 4);
  if (!Number.isFinite(weight) || weight < 0 || !Number.isFinite(pdf) || pdf < 0) failures++;
  if (lobe !== 0 && (lobe & SPECULAR) === 0) {
    worstConsistency = Math.max(worstConsistency, Math.abs(ratio - weight) / Math.max(Math.abs(weight), 1e-3));
  }
  sum += weight;
}
const albedo = sum / sampleCount;
const info = adapter.info ?? {};
console.log(`wgsl_consumer: ${[info.vendor, info.architecture].filter((part) => part).join(' ')}: ${sampleCount} samples, ` +
  `${failures} non-finite or negative, weight vs eval/pdf worst relative ${worstConsistency.toExponential(2)}, white rough metal albedo ${albedo.toFixed(4)}`);
const passed = failures === 0 && worstConsistency <= 1e-3 && Math.abs(albedo - 1) <= 0.01;
console.log(passed ? 'wgsl_consumer: passed' : 'wgsl_consumer: FAILED');
device.destroy();
process.exit(passed ? 0 : 1);
