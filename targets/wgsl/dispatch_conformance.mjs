#!/usr/bin/env node
// dispatch_conformance.mjs: runs a WGSL conformance kernel on WebGPU through Dawn for Node (npm
// `webgpu`) and writes its raw results; it compares nothing. The C++ host
// (host/paths/execution_path.h) writes the inputs, runs this, and compares the results with the
// CPU build under the same per-kind metric as every other path.
//
//   node targets/wgsl/dispatch_conformance.mjs -path NAME -kernel FILE.wgsl [-entry NAME]
//        [-swiftshader ICD.json] [-constant ID=VALUE]... [-mode M] [-repeats N] -dir DIR
//
// Inputs (float32, as host/gpu/cuda_conformance.h writes them): DIR/queries.f32,
// DIR/materials.f32, DIR/lut.f32, DIR/fuzz_ltc.f32. Output: DIR/NAME.results.f32
// (OPENPBR_RESULT_FLOATS per query) and one line on stdout, "NAME: executed on ADAPTER: ..." with
// the pipeline build time and "= T ns/query", or "NAME: skipped: REASON" (exit status 77).
// Bindings (group 0): 0 tables, 1 fuzz table, 2 queries, 3 materials, 4 parameters (query
// count, mode), 5 results: those of every conformance kernel. -constant sets a WGSL `override`
// by its @id (the feature toggles, slang/openpbr_features.h), e.g. -constant 0=false. -mode is
// the kernel's OPENPBR_CONFORMANCE_MODE_* (0 every operation, the default; 1 eval, 2 sample,
// 3 pdf, each with prepare, as `openpbr bench gpu` times them).
//
// The adapter is the first one Dawn offers. Dawn refuses Mesa's lavapipe, so on a machine whose
// only Vulkan driver is lavapipe there is none; then, unless VK_ICD_FILENAMES is already set,
// this program runs itself again with VK_ICD_FILENAMES naming SwiftShader's Vulkan driver
// (-swiftshader: the host passes /usr/lib/chromium/vk_swiftshader_icd.json, from Debian's
// `chromium` package) when that file exists: nobody has to set anything.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const TOOL = 'dispatch_conformance.mjs';
const QUERY_FLOATS = 11; // OPENPBR_QUERY_FLOATS (targets/kernels/openpbr_conformance_kernel.h)
const RESULT_FLOATS = 24; // OPENPBR_RESULT_FLOATS
const WORKGROUP_SIZE = 64; // every conformance kernel's workgroup size
const EXIT_SKIPPED = 77; // as the CUDA conformance program: the path cannot run here
const RETRY_VARIABLE = 'OPENPBR_WGSL_SWIFTSHADER_RETRY';

class UsageError extends Error {}

function parseArgs(argv) {
  const options = { path: null, kernel: null, entry: 'main', swiftshader: null, directory: null, constants: {}, mode: 0, repeats: 3 };
  for (let i = 0; i < argv.length; i++) {
    const value = () => {
      if (i + 1 >= argv.length) throw new UsageError(`${argv[i]} needs a value`);
      return argv[++i];
    };
    switch (argv[i]) {
      case '-path': options.path = value(); break;
      case '-kernel': options.kernel = value(); break;
      case '-entry': options.entry = value(); break;
      case '-swiftshader': options.swiftshader = value(); break;
      case '-dir': options.directory = value(); break;
      case '-repeats': options.repeats = Number(value()); break;
      case '-mode': options.mode = Number(value()); break;
      case '-constant': {
        const match = /^(\d+)=(true|false|[-+0-9.eE]+)$/.exec(value());
        if (!match) throw new UsageError(`-constant needs ID=VALUE (true, false or a number), got '${argv[i]}'`);
        options.constants[match[1]] = match[2] === 'true' ? 1 : match[2] === 'false' ? 0 : Number(match[2]);
        break;
      }
      default: throw new UsageError(`unknown argument '${argv[i]}'`);
    }
  }
  if (!options.path || !options.kernel || !options.directory) throw new UsageError('-path, -kernel and -dir are required');
  if (!Number.isInteger(options.repeats) || options.repeats < 1) throw new UsageError('-repeats needs a whole number >= 1');
  if (![0, 1, 2, 3].includes(options.mode)) throw new UsageError('-mode needs 0 (every operation), 1 (eval), 2 (sample) or 3 (pdf)');
  return options;
}

function readFloats(file) {
  let bytes;
  try {
    bytes = fs.readFileSync(file);
  } catch (error) {
    throw new Error(`cannot read ${file}: ${error.message}`);
  }
  if (bytes.length % 4 !== 0) throw new Error(`${file}: ${bytes.length} bytes is not a whole number of float32 values`);
  // A copy: the file buffer may sit at an offset in a shared pool.
  return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
}

// Dawn's instance: it must stay referenced while its adapter and device are used (a collected
// instance takes them down with a segmentation fault).
let dawnInstance = null;

// The first adapter, or null. The `webgpu` package is imported here, not at the top, so that a
// missing package is reported as a skipped path rather than a crash.
async function firstAdapter(options) {
  let webgpu;
  try {
    webgpu = await import('webgpu');
  } catch (error) {
    return { adapter: null, reason: `npm package 'webgpu' not found (run npm ci): ${error.message}` };
  }
  Object.assign(globalThis, webgpu.globals);
  dawnInstance = webgpu.create([]);
  const adapter = await dawnInstance.requestAdapter();
  const swiftshader = options.swiftshader ? `no SwiftShader at ${options.swiftshader}` : 'no SwiftShader driver given';
  return { adapter, reason: adapter ? '' : `no WebGPU adapter (Dawn refuses lavapipe; ${swiftshader})` };
}

// Runs this program again with SwiftShader as the only Vulkan driver; returns its exit status.
function retryOnSwiftShader(icd) {
  const child = spawnSync(process.execPath, [fileURLToPath(import.meta.url), ...process.argv.slice(2)], {
    stdio: 'inherit',
    env: { ...process.env, VK_ICD_FILENAMES: icd, [RETRY_VARIABLE]: '1' },
  });
  return child.status ?? 1;
}

function adapterName(adapter) {
  const info = adapter.info ?? {};
  return [info.vendor, info.architecture, info.description].filter((part) => part).join(' ') || 'unknown adapter';
}

function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor((sorted.length - 1) / 2)];
}

async function dispatch(adapter, options) {
  const queries = readFloats(path.join(options.directory, 'queries.f32'));
  const materials = readFloats(path.join(options.directory, 'materials.f32'));
  const lut = readFloats(path.join(options.directory, 'lut.f32'));
  const fuzz = readFloats(path.join(options.directory, 'fuzz_ltc.f32'));
  if (queries.length % QUERY_FLOATS !== 0) throw new Error(`queries.f32 is not whole queries of ${QUERY_FLOATS} floats`);
  const queryCount = queries.length / QUERY_FLOATS;
  const source = fs.readFileSync(options.kernel, 'utf8');

  // Six storage buffers, within the default limit of 8 per stage; the largest (results) sized
  // to the batch, so only the binding-size limit is raised, and only as far as needed.
  const resultBytes = Math.max(16, queryCount * RESULT_FLOATS * 4);
  const largest = Math.max(resultBytes, queries.byteLength, materials.byteLength, lut.byteLength, fuzz.byteLength);
  if (largest > adapter.limits.maxStorageBufferBindingSize) {
    throw new Error(`a buffer of ${largest} bytes exceeds the adapter's maxStorageBufferBindingSize ` +
      `${adapter.limits.maxStorageBufferBindingSize}: use fewer queries`);
  }
  const groups = Math.ceil(queryCount / WORKGROUP_SIZE);
  if (groups > adapter.limits.maxComputeWorkgroupsPerDimension) throw new Error(`${queryCount} queries need too many workgroups`);
  const timestamps = adapter.features.has('timestamp-query');
  const device = await adapter.requestDevice({
    label: 'conformance device',
    requiredFeatures: timestamps ? ['timestamp-query'] : [],
    requiredLimits: { maxStorageBufferBindingSize: Math.max(largest, 134217728) },
  });
  const errors = [];
  device.addEventListener('uncapturederror', (event) => errors.push(event.error.message));
  try {
    device.pushErrorScope('validation');
    const module = device.createShaderModule({ label: `${options.path} kernel`, code: source });
    const compilation = await module.getCompilationInfo();
    const compileErrors = compilation.messages.filter((message) => message.type === 'error');
    if (compileErrors.length > 0) {
      throw new Error(`${options.kernel}: ${compileErrors.map((m) => `${m.lineNum}:${m.linePos}: ${m.message}`).join('; ')}`);
    }
    const pipelineStart = performance.now();
    const pipeline = await device.createComputePipelineAsync({
      label: `${options.path} pipeline`,
      layout: 'auto',
      compute: { module, entryPoint: options.entry, constants: options.constants },
    });
    const pipelineMs = performance.now() - pipelineStart;

    const storage = (label, data, usage) => {
      const buffer = device.createBuffer({ label, size: Math.max(16, data.byteLength), usage: GPUBufferUsage.STORAGE | usage });
      device.queue.writeBuffer(buffer, 0, data);
      return buffer;
    };
    const copyDestination = GPUBufferUsage.COPY_DST;
    const buffers = [
      storage('tables', lut, copyDestination),
      storage('fuzz table', fuzz, copyDestination),
      storage('queries', queries, copyDestination),
      storage('materials', materials, copyDestination),
      storage('parameters', new Uint32Array([queryCount, options.mode, 0, 0]), copyDestination),
      device.createBuffer({ label: 'results', size: resultBytes, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC }),
    ];
    // The kernel's layout is derived from its WGSL ('auto'), which holds only the bindings the
    // entry point uses: each of the six is used by every conformance kernel.
    const bindGroup = device.createBindGroup({
      label: `${options.path} bindings`,
      layout: pipeline.getBindGroupLayout(0),
      entries: buffers.map((buffer, binding) => ({ binding, resource: { buffer } })),
    });
    const readback = device.createBuffer({ label: 'results readback', size: resultBytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    const querySet = timestamps ? device.createQuerySet({ label: 'dispatch timestamps', type: 'timestamp', count: 2 }) : null;
    const resolve = timestamps ? device.createBuffer({ label: 'timestamps', size: 16, usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC }) : null;
    const resolveRead = timestamps ? device.createBuffer({ label: 'timestamps readback', size: 16, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST }) : null;

    // Each repeat is one submission, waited for: the first includes SwiftShader's shader
    // compilation where it defers it; the steady-state time is the median of the others.
    const wallMs = [];
    const deviceMs = [];
    for (let repeat = 0; repeat < options.repeats; repeat++) {
      const encoder = device.createCommandEncoder({ label: `${options.path} dispatch ${repeat}` });
      const pass = encoder.beginComputePass(timestamps
        ? { timestampWrites: { querySet, beginningOfPassWriteIndex: 0, endOfPassWriteIndex: 1 } }
        : {});
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bindGroup);
      pass.dispatchWorkgroups(groups);
      pass.end();
      if (timestamps) {
        encoder.resolveQuerySet(querySet, 0, 2, resolve, 0);
        encoder.copyBufferToBuffer(resolve, 0, resolveRead, 0, 16);
      }
      if (repeat === options.repeats - 1) encoder.copyBufferToBuffer(buffers[5], 0, readback, 0, resultBytes);
      const start = performance.now();
      device.queue.submit([encoder.finish()]);
      await device.queue.onSubmittedWorkDone();
      wallMs.push(performance.now() - start);
      if (timestamps) {
        await resolveRead.mapAsync(GPUMapMode.READ);
        const [begin, end] = new BigUint64Array(resolveRead.getMappedRange().slice(0));
        resolveRead.unmap();
        // Negative or zero deltas come from unreliable timestamps: dropped.
        if (end > begin) deviceMs.push(Number(end - begin) * 1e-6);
      }
    }
    await readback.mapAsync(GPUMapMode.READ);
    const results = new Float32Array(readback.getMappedRange().slice(0));
    readback.unmap();
    const scopeError = await device.popErrorScope();
    if (scopeError) throw new Error(`WebGPU validation: ${scopeError.message}`);
    if (errors.length > 0) throw new Error(`WebGPU error: ${errors[0]}`);

    const steady = (values) => median(values.length > 1 ? values.slice(1) : values);
    const timed = deviceMs.length > 0 ? deviceMs : wallMs;
    const nsPerQuery = queryCount > 0 ? (steady(timed) * 1e6) / queryCount : 0;
    fs.writeFileSync(path.join(options.directory, `${options.path}.results.f32`), Buffer.from(results.buffer));
    const clock = deviceMs.length > 0 ? 'timestamp queries' : 'submit to work done';
    console.log(`${options.path}: executed on ${adapterName(adapter)}: pipeline ${pipelineMs.toFixed(0)} ms, ` +
      `first dispatch ${wallMs[0].toFixed(0)} ms, dispatch = ${nsPerQuery.toPrecision(4)} ns/query (${clock}, ` +
      `median after the first of ${options.repeats})`);
  } finally {
    device.destroy();
  }
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  const { adapter, reason } = await firstAdapter(options);
  if (!adapter) {
    const icd = options.swiftshader;
    if (icd && !process.env.VK_ICD_FILENAMES && !process.env[RETRY_VARIABLE] && fs.existsSync(icd)) {
      process.exit(retryOnSwiftShader(icd));
    }
    console.log(`${options.path}: skipped: ${reason}`);
    process.exit(EXIT_SKIPPED);
  }
  await dispatch(adapter, options);
  // Dawn keeps Node alive while its instance is referenced: exit explicitly.
  process.exit(0);
}

main().catch((error) => {
  if (error instanceof UsageError) {
    console.error(`${TOOL}: error: ${error.message}`);
    process.exit(2);
  }
  console.error(`${TOOL}: error: ${error.message}`);
  process.exit(1);
});
