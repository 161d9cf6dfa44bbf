// The WebGPU side of the viewer: the material analysis, the render kernel's three step entry
// points (targets/kernels/render_steps.slang) specialized per feature set, and the display
// pass. Pipelines are built once per feature set and kept; a material change only rewrites
// buffers and clears the accumulation.
import { required } from './layout.mjs';

const STORAGE = GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | GPUBufferUsage.COPY_SRC;
const RENDER_BINDINGS = 8; // tables (2), parameters, scene, materials, accumulation, path states, active count
const PATH_STATE_FLOATS = 24; // RENDER_PATH_STATE_FLOATS in render_steps.slang
const ANALYSIS_HEADER = 4; // VIEWER_RECORD_HEADER in object_record.slang
const ANALYSIS_EXTRA = 4; // VIEWER_RECORD_EXTRA

const KERNEL_RETRIES = 20; // answers "busy" (503) in a row before a kernel request fails, e.g. 60
const RETRY_LIMIT_SECONDS = 60; // the longest wait between them, whatever Retry-After says, e.g. 120

// fetch(url), with a failure to reach the server and an answer other than 2xx as errors that
// say what was asked for and the server's message. `busyIsAnswer`: a 503 is returned, not thrown.
async function fetchOk(url, what, busyIsAnswer = false) {
  let response;
  try {
    response = await fetch(url);
  } catch (error) {
    throw new Error(`${what}: the server did not answer (${error.message})`);
  }
  if (response.ok || (busyIsAnswer && response.status === 503)) return response;
  throw new Error(`${what}: ${(await response.text()).trim().slice(0, 4000) || `HTTP ${response.status}`}`);
}

// A kernel's WGSL from the server, which compiles it on request. `onPhase('compile')` while it
// compiles; a busy server (503: its compile queue is full) is asked again after its Retry-After,
// with `onPhase('wait', seconds)` before each wait.
async function fetchKernel(url, what, onPhase) {
  for (let attempt = 1; ; attempt++) {
    onPhase('compile');
    const response = await fetchOk(url, what, attempt < KERNEL_RETRIES);
    if (response.ok) return response;
    const seconds = Math.min(RETRY_LIMIT_SECONDS, Math.max(1, Number(response.headers.get('retry-after')) || 5));
    onPhase('wait', seconds);
    await new Promise((resolve) => setTimeout(resolve, seconds * 1000));
  }
}

// The device, with the storage-buffer count the render kernel needs checked first.
export async function createDevice(onError) {
  if (!navigator.gpu) throw new Error('WebGPU is not available in this browser (navigator.gpu is missing)');
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error('WebGPU: no adapter');
  if (adapter.limits.maxStorageBuffersPerShaderStage < RENDER_BINDINGS) {
    throw new Error(`WebGPU: the adapter allows ${adapter.limits.maxStorageBuffersPerShaderStage} storage buffers per stage; the render kernel needs ${RENDER_BINDINGS}`);
  }
  const device = await adapter.requestDevice({
    label: 'viewer.device',
    requiredLimits: { maxStorageBuffersPerShaderStage: RENDER_BINDINGS },
  });
  device.addEventListener('uncapturederror', (event) => onError(`WebGPU error: ${event.error.message}`));
  device.lost.then((info) => onError(`WebGPU device lost (${info.reason}): ${info.message}`));
  const info = adapter.info ?? {};
  return { device, adapterName: [info.vendor, info.architecture, info.description].filter(Boolean).join(' ') };
}

function storageBuffer(device, label, data) {
  const buffer = device.createBuffer({ label, size: Math.max(16, Math.ceil(data.byteLength / 16) * 16), usage: STORAGE });
  device.queue.writeBuffer(buffer, 0, data);
  return buffer;
}

async function readBuffer(device, source, size, label) {
  const staging = device.createBuffer({ label, size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  const encoder = device.createCommandEncoder({ label: `${label}.encoder` });
  encoder.copyBufferToBuffer(source, 0, staging, 0, size);
  device.queue.submit([encoder.finish()]);
  await staging.mapAsync(GPUMapMode.READ);
  const data = staging.getMappedRange().slice(0);
  staging.unmap();
  staging.destroy();
  return data;
}

export class Renderer {
  // `kernel`: integer defines of openpbr_render_kernel.h; `packedFloats`: floats per material.
  constructor(device, context, format, kernel, packedFloats) {
    this.device = device;
    this.context = context;
    this.kernel = kernel;
    this.packedFloats = packedFloats;
    this.recordFloats = required(kernel, 'OPENPBR_RENDER_ACCUMULATION_FLOATS', 'openpbr_render_kernel.h');
    this.objectFloats = required(kernel, 'OPENPBR_RENDER_OBJECT_FLOATS', 'openpbr_render_kernel.h');
    this.format = format;
    this.pipelines = new Map(); // feature mask -> Promise of { begin, step, end, buildSeconds }
    this.size = 0;
  }

  // The tables, the material analysis kernel and the display pass. `onPhase(phase, seconds)`:
  // 'compile' (the server compiles the kernel), 'wait' (the server is busy), 'pipelines'.
  async init(displayCode, onPhase = () => {}) {
    const device = this.device;
    const [lut, fuzz] = await Promise.all([
      fetchOk('/api/tables/lut.bin', 'energy-compensation table').then((r) => r.arrayBuffer()),
      fetchOk('/api/tables/fuzz_ltc.bin', 'fuzz LTC table').then((r) => r.arrayBuffer()),
    ]);
    this.lut = storageBuffer(device, 'viewer.table.lut', lut);
    this.fuzz = storageBuffer(device, 'viewer.table.fuzz_ltc', fuzz);
    this.activeCount = device.createBuffer({ label: 'viewer.active_count', size: 16, usage: STORAGE });
    this.activeReadback = device.createBuffer({
      label: 'viewer.active_count.readback', size: 16, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    });

    const entries = [];
    for (let binding = 0; binding < RENDER_BINDINGS; binding++) {
      const readOnly = binding < 5;
      entries.push({ binding, visibility: GPUShaderStage.COMPUTE, buffer: { type: readOnly ? 'read-only-storage' : 'storage' } });
    }
    this.renderLayout = device.createBindGroupLayout({ label: 'viewer.render.bindGroupLayout', entries });
    this.renderPipelineLayout = device.createPipelineLayout({ label: 'viewer.render.pipelineLayout', bindGroupLayouts: [this.renderLayout] });

    const analysisResponse = await fetchKernel('/api/kernel/object_record.wgsl', 'material analysis kernel', onPhase);
    const analysisCode = await analysisResponse.text();
    onPhase('pipelines');
    const analysisModule = device.createShaderModule({ label: 'viewer.object_record.module', code: analysisCode });
    this.analysisLayout = device.createBindGroupLayout({
      label: 'viewer.object_record.bindGroupLayout',
      entries: [
        { binding: 2, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'read-only-storage' } },
        { binding: 3, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'storage' } },
      ],
    });
    this.analysisPipeline = await device.createComputePipelineAsync({
      label: 'viewer.object_record.pipeline',
      layout: device.createPipelineLayout({ label: 'viewer.object_record.pipelineLayout', bindGroupLayouts: [this.analysisLayout] }),
      compute: { module: analysisModule, entryPoint: 'object_record_main' },
    });

    const displayModule = device.createShaderModule({ label: 'viewer.display.module', code: displayCode });
    this.displayLayout = device.createBindGroupLayout({
      label: 'viewer.display.bindGroupLayout',
      entries: [
        { binding: 0, visibility: GPUShaderStage.FRAGMENT, buffer: { type: 'read-only-storage' } },
        { binding: 1, visibility: GPUShaderStage.FRAGMENT, buffer: { type: 'uniform' } },
      ],
    });
    this.displayPipeline = await device.createRenderPipelineAsync({
      label: 'viewer.display.pipeline',
      layout: device.createPipelineLayout({ label: 'viewer.display.pipelineLayout', bindGroupLayouts: [this.displayLayout] }),
      vertex: { module: displayModule, entryPoint: 'vertex_main' },
      fragment: { module: displayModule, entryPoint: 'fragment_main', targets: [{ format: this.format }] },
      primitive: { topology: 'triangle-list' },
    });
    this.displayUniform = device.createBuffer({ label: 'viewer.display.uniform', size: 32, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  }

  // Runs the library's analysis on packed materials: per material its object record (16 floats)
  // and required feature mask; also the default wavelengths.
  async analyze(packedMaterials, count) {
    const device = this.device;
    const input = storageBuffer(device, 'viewer.object_record.materials', packedMaterials);
    const outputSize = (ANALYSIS_HEADER + count * (this.objectFloats + ANALYSIS_EXTRA)) * 4;
    const output = device.createBuffer({ label: 'viewer.object_record.output', size: outputSize, usage: STORAGE });
    const bindGroup = device.createBindGroup({
      label: 'viewer.object_record.bindGroup',
      layout: this.analysisLayout,
      entries: [{ binding: 2, resource: { buffer: input } }, { binding: 3, resource: { buffer: output } }],
    });
    const encoder = device.createCommandEncoder({ label: 'viewer.object_record.encoder' });
    const pass = encoder.beginComputePass({ label: 'viewer.object_record.pass' });
    pass.setPipeline(this.analysisPipeline);
    pass.setBindGroup(0, bindGroup);
    pass.dispatchWorkgroups(count);
    pass.end();
    device.queue.submit([encoder.finish()]);
    const data = new Float32Array(await readBuffer(device, output, outputSize, 'viewer.object_record.readback'));
    input.destroy();
    output.destroy();
    const stride = this.objectFloats + ANALYSIS_EXTRA;
    const materials = [];
    for (let i = 0; i < count; i++) {
      const base = ANALYSIS_HEADER + i * stride;
      materials.push({ record: data.slice(base, base + this.objectFloats), mask: data[base + this.objectFloats] });
    }
    return { wavelengths: data.slice(0, 3), materials };
  }

  // The render kernel's pipelines for a feature set, built on first use (the WGSL is generated
  // by the server, specialized to the set). `label`: the set's name for messages, e.g.
  // "coat+metal"; `onPhase` as for init() (the caller that starts the build gets the calls).
  pipelinesFor(mask, label = String(mask), onPhase = () => {}) {
    if (!this.pipelines.has(mask)) {
      const build = async () => {
        const what = `render kernel {${label}}`;
        const response = await fetchKernel(`/api/kernel/render.wgsl?features=${mask}`, what, onPhase);
        const compileSeconds = Number(response.headers.get('x-compile-seconds'));
        const code = await response.text();
        onPhase('pipelines');
        const start = performance.now();
        const module = this.device.createShaderModule({ label: `viewer.render.module[${mask}]`, code });
        const make = (entryPoint) => this.device.createComputePipelineAsync({
          label: `viewer.render.${entryPoint}[${mask}]`,
          layout: this.renderPipelineLayout,
          compute: { module, entryPoint },
        }).catch((error) => {
          throw new Error(`${what}: building the ${entryPoint} pipeline failed: ${error.message}`);
        });
        const [begin, step, end] = await Promise.all(['render_begin_main', 'render_step_main', 'render_end_main'].map(make));
        return { begin, step, end, compileSeconds, buildSeconds: (performance.now() - start) / 1000 };
      };
      const promise = build();
      promise.catch(() => this.pipelines.delete(mask));
      this.pipelines.set(mask, promise);
    }
    return this.pipelines.get(mask);
  }

  // Sets the image size and the scene; clears the accumulation.
  setScene(size, parameters, scene, packedMaterials) {
    const device = this.device;
    if (size !== this.size) {
      this.accumulation?.destroy();
      this.pathStates?.destroy();
      this.accumulation = device.createBuffer({ label: 'viewer.accumulation', size: size * size * this.recordFloats * 4, usage: STORAGE });
      this.pathStates = device.createBuffer({ label: 'viewer.path_states', size: size * size * PATH_STATE_FLOATS * 4, usage: STORAGE });
      this.size = size;
    }
    this.parameters = parameters;
    this.parameterBuffer?.destroy();
    this.sceneBuffer?.destroy();
    this.materialBuffer?.destroy();
    this.parameterBuffer = storageBuffer(device, 'viewer.parameters', parameters);
    this.sceneBuffer = storageBuffer(device, 'viewer.scene', scene);
    this.materialBuffer = storageBuffer(device, 'viewer.materials', packedMaterials);
    const buffers = [this.lut, this.fuzz, this.parameterBuffer, this.sceneBuffer, this.materialBuffer, this.accumulation, this.pathStates, this.activeCount];
    this.renderBindGroup = device.createBindGroup({
      label: 'viewer.render.bindGroup',
      layout: this.renderLayout,
      entries: buffers.map((buffer, binding) => ({ binding, resource: { buffer } })),
    });
    this.displayBindGroup = device.createBindGroup({
      label: 'viewer.display.bindGroup',
      layout: this.displayLayout,
      entries: [{ binding: 0, resource: { buffer: this.accumulation } }, { binding: 1, resource: { buffer: this.displayUniform } }],
    });
    const encoder = device.createCommandEncoder({ label: 'viewer.clear.encoder' });
    encoder.clearBuffer(this.accumulation);
    device.queue.submit([encoder.finish()]);
  }

  dispatch(encoder, label, pipeline, count) {
    const groups = Math.ceil(this.size / 8);
    const pass = encoder.beginComputePass({ label });
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, this.renderBindGroup);
    for (let i = 0; i < count; i++) pass.dispatchWorkgroups(groups, groups);
    pass.end();
  }

  // Adds sample `index` to every pixel: begin, steps until no path is running (the count of
  // the last step of each batch is read back), end. `firstBatch` steps are dispatched before
  // the first check (max_depth + 2 ends every path without a medium), then `batch` at a time.
  async renderSample(pipelines, index, firstBatch, batch) {
    const device = this.device;
    const sampleIndex = required(this.kernel, 'OPENPBR_RENDER_PARAMETER_SAMPLE_BEGIN', 'openpbr_render_kernel.h');
    this.parameters[sampleIndex] = index;
    device.queue.writeBuffer(this.parameterBuffer, 0, this.parameters);
    let steps = firstBatch;
    let encoder = device.createCommandEncoder({ label: 'viewer.sample.encoder' });
    this.dispatch(encoder, 'viewer.sample.begin', pipelines.begin, 1);
    for (;;) {
      this.dispatch(encoder, 'viewer.sample.steps', pipelines.step, steps - 1);
      encoder.clearBuffer(this.activeCount);
      this.dispatch(encoder, 'viewer.sample.counted_step', pipelines.step, 1);
      encoder.copyBufferToBuffer(this.activeCount, 0, this.activeReadback, 0, 16);
      device.queue.submit([encoder.finish()]);
      await this.activeReadback.mapAsync(GPUMapMode.READ);
      const active = new Uint32Array(this.activeReadback.getMappedRange())[0];
      this.activeReadback.unmap();
      encoder = device.createCommandEncoder({ label: 'viewer.sample.encoder' });
      if (active === 0) break;
      steps = batch;
    }
    this.dispatch(encoder, 'viewer.sample.end', pipelines.end, 1);
    device.queue.submit([encoder.finish()]);
  }

  display(samples, exposure) {
    if (!this.displayBindGroup) return; // no scene yet
    const device = this.device;
    const uniform = new ArrayBuffer(32);
    new Uint32Array(uniform, 0, 4).set([this.size, this.size, samples, this.recordFloats]);
    new Float32Array(uniform, 16, 1)[0] = exposure;
    device.queue.writeBuffer(this.displayUniform, 0, uniform);
    const encoder = device.createCommandEncoder({ label: 'viewer.display.encoder' });
    const pass = encoder.beginRenderPass({
      label: 'viewer.display.pass',
      colorAttachments: [{ view: this.context.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 1] }],
    });
    pass.setPipeline(this.displayPipeline);
    pass.setBindGroup(0, this.displayBindGroup);
    pass.draw(3);
    pass.end();
    device.queue.submit([encoder.finish()]);
  }

  // The accumulation records (OPENPBR_RENDER_ACCUMULATION_FLOATS floats per pixel).
  async readAccumulation() {
    return new Float32Array(await readBuffer(this.device, this.accumulation, this.size * this.size * this.recordFloats * 4, 'viewer.accumulation.readback'));
  }
}
