// The OpenPBR material viewer: a progressive path tracer of one material sphere on the ground
// under the sky of `openpbr render`, running that renderer's kernel compiled to WGSL and
// specialized to the features the material uses. URL options: material=<file stem of
// materials/*.mtlx>, size=<pixels> (default 512), spp=<samples to stop at> (default 4096),
// seed=<n> (default 1).
import { buildControls } from './controls.mjs';
import { integerDefines, required } from './layout.mjs';
import { defaultValues, packMaterial } from './material.mjs';
import { MaterialError, parseMaterialX } from './materialx.mjs';
import { parseParameterTable } from './parameters.mjs';
import { createDevice, Renderer } from './renderer.mjs';
import { groundValues, makeParameters, makeScene, RENDER_DEFAULTS } from './scene.mjs';

const $ = (id) => document.getElementById(id);
const options = new URLSearchParams(location.search);
const settings = {
  ...RENDER_DEFAULTS,
  seed: Number(options.get('seed') ?? RENDER_DEFAULTS.seed),
  size: Number(options.get('size') ?? 512),
  sampleLimit: Number(options.get('spp') ?? 4096),
};

const stats = { adapter: '', generation: 0, firstImageSeconds: null, samples: 0, sampleTimes: [], mask: null, features: '', kernel: null };
let errorText = '';

function showError(message) {
  errorText = message;
  const box = $('error');
  box.textContent = message;
  box.hidden = false;
}

function clearError() {
  errorText = '';
  $('error').hidden = true;
}

function setStatus(text) {
  $('status').textContent = text;
}

// The caption under the image says what the page is doing. Work under way counts its seconds,
// e.g. "open_pbr_carpaint: compiling kernel {coat}… 12 s"; a result stops the count.
const caption = {
  timer: null,
  work(text) {
    const since = performance.now();
    const show = () => {
      const counted = `${text}… ${Math.floor((performance.now() - since) / 1000)} s`;
      if ($('status').textContent !== counted) setStatus(counted);
    };
    this.done(null);
    show();
    this.timer = setInterval(show, 250);
  },
  done(text) {
    clearInterval(this.timer);
    this.timer = null;
    if (text !== null) setStatus(text);
  },
};

// The caption for a kernel's phases (Renderer's onPhase): `subject` names the kernel, e.g.
// "kernel {coat}" or "the material analysis kernel"; `prefix` the material, e.g. "carpaint: ".
function phaseCaption(prefix, subject) {
  return (phase, seconds) => {
    if (phase === 'compile') caption.work(`${prefix}compiling ${subject}`);
    else if (phase === 'wait') caption.work(`${prefix}the server's compile queue is full; asking again for ${subject} in ${seconds} s`);
    else caption.work(`${prefix}building the pipelines of ${subject}`);
  };
}

async function text(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${await response.text()}`);
  return response.text();
}

const state = { renderer: null, table: null, values: null, generation: 0, running: null, toggles: [], name: '' };

function featureLabel(mask) {
  const names = state.toggles.filter((toggle) => (mask & toggle.bit) !== 0).map((toggle) => toggle.name);
  return names.length > 0 ? names.join('+') : 'base';
}

// Restarts accumulation for the current values: analysis, the specialized kernel, then samples.
async function restart() {
  const generation = ++state.generation;
  const renderer = state.renderer;
  await state.running;
  if (generation !== state.generation) return;
  stats.generation = generation;
  stats.samples = 0;
  stats.sampleTimes = [];
  $('samples').textContent = '0 spp';
  const floats = state.packedFloats;
  const packed = new Float32Array(2 * floats);
  packed.set(packMaterial(state.table, state.values, floats), 0);
  packed.set(packMaterial(state.table, groundValues(defaultValues(state.table)), floats), floats);
  let step = 'the material analysis';
  const run = (async () => {
    try {
      caption.work(`${state.name}: analysing the material`);
      const analysis = await renderer.analyze(packed, 2);
      // The smallest feature set that renders the sphere and the ground exactly (scene_feature_mask).
      const mask = analysis.materials[0].mask | analysis.materials[1].mask;
      stats.mask = mask;
      stats.features = featureLabel(mask);
      step = `kernel {${stats.features}}`;
      const pipelines = await renderer.pipelinesFor(mask, stats.features, phaseCaption(`${state.name}: `, step));
      stats.kernel = { compileSeconds: pipelines.compileSeconds, buildSeconds: pipelines.buildSeconds };
      if (generation !== state.generation) return;
      const parameters = makeParameters(state.kernel, settings.size, settings);
      renderer.setScene(settings.size, parameters, makeScene(state.kernel, analysis.materials[0].record, analysis.wavelengths), packed);
      step = `rendering with kernel {${stats.features}}`;
      caption.done(`${state.name}: kernel {${stats.features}} (WGSL ${pipelines.compileSeconds.toFixed(1)} s, pipelines ${pipelines.buildSeconds.toFixed(1)} s)`);
      const firstBatch = settings.maxDepth + 2;
      while (generation === state.generation && stats.samples < settings.sampleLimit) {
        await renderer.renderSample(pipelines, stats.samples, firstBatch, 8);
        stats.samples += 1;
        renderer.display(stats.samples, Number($('exposure').value));
        await renderer.device.queue.onSubmittedWorkDone();
        stats.sampleTimes.push(performance.now() / 1000);
        if (stats.firstImageSeconds === null) stats.firstImageSeconds = performance.now() / 1000;
        $('samples').textContent = `${stats.samples} spp`;
      }
    } catch (error) {
      caption.done(`${state.name}: ${step} failed; the message is above the image`);
      showError(error.message);
    }
  })();
  state.running = run;
}

function applyMaterial(material) {
  state.values = { ...defaultValues(state.table), ...material.values };
  state.name = material.name;
  state.setControls(state.values);
  clearError();
  return restart();
}

// Loads the materials of a .mtlx text (dropped, picked or fetched); the first is shown, all are
// added to the picker. A file the C++ loader would refuse is refused here, with its message
// (and false). Returns the generation whose samples state() reports once they start.
function loadMaterialText(source, file) {
  let materials;
  try {
    materials = parseMaterialX(source, file, state.table);
  } catch (error) {
    showError(error instanceof MaterialError ? error.message : `${file}: ${error.message}`);
    return Promise.resolve(false);
  }
  const picker = $('material');
  for (const material of materials) {
    const option = document.createElement('option');
    option.value = `dropped:${picker.options.length}`;
    option.textContent = `${material.name} (${file})`;
    option.material = material;
    picker.append(option);
  }
  picker.value = picker.options[picker.options.length - materials.length].value;
  applyMaterial(materials[0]);
  return Promise.resolve(state.generation);
}

async function loadBundled(file) {
  let materials;
  try {
    materials = parseMaterialX(await text(`/materials/${file}`), file, state.table);
  } catch (error) {
    caption.done(`${file} could not be loaded; the message is above the image`);
    throw error;
  }
  return applyMaterial(materials[0]);
}

function setupDrop() {
  const target = document.body;
  target.addEventListener('dragover', (event) => { event.preventDefault(); target.classList.add('dragging'); });
  target.addEventListener('dragleave', () => target.classList.remove('dragging'));
  target.addEventListener('drop', async (event) => {
    event.preventDefault();
    target.classList.remove('dragging');
    const file = [...event.dataTransfer.files].find((f) => f.name.endsWith('.mtlx')) ?? event.dataTransfer.files[0];
    if (!file) return;
    loadMaterialText(await file.text(), file.name);
  });
}

async function main() {
  const [parametersHeader, packingHeader, kernelHeader, displayCode, toggles, bundled] = await Promise.all([
    text('/slang/openpbr_parameters.h'), text('/slang/openpbr_material_packing.h'),
    text('/targets/kernels/openpbr_render_kernel.h'), text('/viewer/display.wgsl'),
    text('/api/features').then(JSON.parse), text('/api/materials').then(JSON.parse),
  ]);
  state.table = parseParameterTable(parametersHeader);
  state.packedFloats = required(integerDefines(packingHeader), 'OPENPBR_PACKED_MATERIAL_FLOATS', 'openpbr_material_packing.h');
  state.kernel = integerDefines(kernelHeader);
  state.toggles = toggles;

  const canvas = $('canvas');
  canvas.width = settings.size;
  canvas.height = settings.size;
  const { device, adapterName } = await createDevice(showError);
  $('adapter').textContent = adapterName;
  stats.adapter = adapterName;
  const context = canvas.getContext('webgpu');
  const format = navigator.gpu.getPreferredCanvasFormat();
  context.configure({ device, format, alphaMode: 'opaque' });
  state.renderer = new Renderer(device, context, format, state.kernel, state.packedFloats);
  await state.renderer.init(displayCode, phaseCaption('', 'the material analysis kernel'));
  caption.work('loading the material');

  state.setControls = buildControls($('controls'), state.table, (name, value) => {
    state.values[name] = value;
    restart();
  });
  const picker = $('material');
  for (const file of bundled) {
    const option = document.createElement('option');
    option.value = file;
    option.textContent = file.replace(/^open_pbr_/, '').replace(/\.mtlx$/, '').replace(/_/g, ' ');
    picker.append(option);
  }
  picker.addEventListener('change', () => {
    const option = picker.selectedOptions[0];
    if (option.material) applyMaterial(option.material);
    else loadBundled(option.value).catch((error) => showError(error.message));
  });
  $('exposure').addEventListener('input', () => state.renderer.display(stats.samples, Number($('exposure').value)));
  $('file').addEventListener('change', async () => {
    const file = $('file').files[0];
    if (file) loadMaterialText(await file.text(), file.name);
  });
  setupDrop();

  const wanted = `${options.get('material') ?? 'open_pbr_default'}.mtlx`;
  picker.value = bundled.includes(wanted) ? wanted : bundled[0];
  loadBundled(picker.value).catch((error) => showError(error.message));
}

// For the browser test (tests/viewer) and for scripts: the page's state and its image.
window.openpbrViewer = {
  state: () => ({ ...stats, sampleTimes: undefined, error: errorText, name: state.name, settings, status: $('status').textContent }),
  loadMaterialText,
  // Parses a .mtlx text without loading it: the material names, or the error message.
  parse(source, file) {
    try {
      return parseMaterialX(source, file, state.table).map((material) => material.name);
    } catch (error) {
      return error.message;
    }
  },
  // Builds (or finds) the render kernel of a feature mask: { compileSeconds, buildSeconds }.
  async buildKernel(mask) {
    const { compileSeconds, buildSeconds } = await state.renderer.pipelinesFor(mask, featureLabel(mask));
    return { compileSeconds, buildSeconds };
  },
  samplesPerSecond() {
    const times = stats.sampleTimes;
    return times.length > 2 ? (times.length - 1) / (times[times.length - 1] - times[0]) : null;
  },
  // Mean radiance per pixel and channel (rows from the top), and the sample count it is over.
  async readMean() {
    const records = await state.renderer.readAccumulation();
    const floats = required(state.kernel, 'OPENPBR_RENDER_ACCUMULATION_FLOATS', 'openpbr_render_kernel.h');
    const n = stats.samples;
    const mean = new Array((records.length / floats) * 3);
    for (let pixel = 0; pixel < records.length / floats; pixel++) {
      for (let channel = 0; channel < 3; channel++) mean[pixel * 3 + channel] = records[pixel * floats + channel] / n;
    }
    return { samples: n, size: settings.size, mean };
  },
};

main().catch((error) => {
  caption.done('the viewer could not start; the message is above the image');
  showError(error.message);
});
