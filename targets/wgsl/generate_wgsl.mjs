#!/usr/bin/env node
// generate_wgsl.mjs: writes openpbr.wgsl, the self-contained WGSL library of the OpenPBR BSDF
// for WebGPU engines, from the Slang module (targets/wgsl/openpbr_wgsl.slang through
// targets/slangc.mjs, Slang's WGSL target), as openpbr.hlsl is for HLSL.
//
//   node targets/wgsl/generate_wgsl.mjs -I slang [-D NAME=VALUE]... [-append KERNEL.wgsl] -o openpbr.wgsl
//
// -append copies a WGSL file after the library (WGSL has no #include), e.g. the conformance
// kernel of path "wgsl-library" (targets/wgsl/conformance.wgsl).
//
// -D defines go to Slang as text before the module (targets/slangc.mjs): a feature toggle
// defined here is folded when the library is generated (e.g. -D OPENPBR_FEATURE_COAT=0; the
// names are in slang/openpbr_features.h), which drivers that do not fold WGSL `override`s
// before compiling (SwiftShader) compile faster (docs/performance.md); toggles left undefined stay
// `override` constants, set through the pipeline's `constants` by their @id.
//
// Slang names every WGSL declaration with a numeric suffix (openpbr_eval_0, base_color_0). The
// generator gives the library's names their plain spelling, so an engine writes openpbr_eval and
// inputs.base_color: a global openpbr_*/OpenPBR_* function, struct, override or variable whose
// base name occurs once, and every struct field. Slang's export wrappers (openpbr_export_X of
// openpbr_wgsl.slang) become X where Slang inlined X into them, and are dropped where it did not.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const TOOL = 'generate_wgsl.mjs';
const HERE = path.dirname(fileURLToPath(import.meta.url));
const EXPORT_PREFIX = 'openpbr_export_';

class UsageError extends Error {}

function parseArgs(argv) {
  const options = { includeDirs: [], defines: [], appended: [], output: null };
  for (let i = 0; i < argv.length; i++) {
    const value = () => {
      if (i + 1 >= argv.length) throw new UsageError(`${argv[i]} needs a value`);
      return argv[++i];
    };
    switch (argv[i]) {
      case '-I': options.includeDirs.push(value()); break;
      case '-D': options.defines.push(value()); break;
      case '-append': options.appended.push(value()); break;
      case '-o': options.output = value(); break;
      default: throw new UsageError(`unknown argument '${argv[i]}'`);
    }
  }
  if (!options.output) throw new UsageError('-o FILE is required');
  return options;
}

function slangToWgsl(options) {
  const temporary = path.join(fs.mkdtempSync(path.join(fs.realpathSync(process.env.TMPDIR ?? '/tmp'), 'openpbr-wgsl-')), 'library.wgsl');
  const args = [path.join(HERE, '..', 'slangc.mjs'), '-q', '-target', 'wgsl'];
  for (const dir of options.includeDirs) args.push('-I', dir);
  for (const define of options.defines) args.push('-D', define);
  args.push('-o', temporary, path.join(HERE, 'openpbr_wgsl.slang'));
  const run = spawnSync(process.execPath, args, { stdio: ['ignore', 'inherit', 'inherit'] });
  if (run.status !== 0) throw new Error(`slangc.mjs failed (status ${run.status})`);
  const text = fs.readFileSync(temporary, 'utf8');
  fs.rmSync(path.dirname(temporary), { recursive: true, force: true });
  return text;
}

// The top-level functions: name -> [start, end) character range of the whole declaration.
function functionRanges(text) {
  const ranges = new Map();
  const header = /^fn (\w+)\(/gm;
  for (let match = header.exec(text); match; match = header.exec(text)) {
    const open = text.indexOf('\n{', match.index);
    const close = text.indexOf('\n}\n', open);
    if (open < 0 || close < 0) throw new Error(`cannot find the body of ${match[1]}`);
    ranges.set(match[1], [match.index, close + 3]);
  }
  return ranges;
}

function globalNames(text) {
  const names = new Set();
  const patterns = [/^fn (\w+)\(/gm, /^struct (\w+)/gm, /^@id\(\d+\) override (\w+)/gm, /^@binding\(\d+\) @group\(\d+\) var<[^>]*> (\w+)/gm];
  for (const pattern of patterns) {
    for (const match of text.matchAll(pattern)) names.add(match[1]);
  }
  return names;
}

function replaceToken(text, from, to) {
  return text.replace(new RegExp(`\\b${from}\\b`, 'g'), to);
}

function plainNames(slangText) {
  let text = slangText;
  // Export wrappers: openpbr_export_X_N -> X where X was inlined, else the wrapper goes.
  const functions = functionRanges(text);
  const wrappers = [...functions.keys()].filter((name) => name.startsWith(EXPORT_PREFIX));
  for (const wrapper of wrappers.sort((a, b) => functions.get(b)[0] - functions.get(a)[0])) {
    const base = wrapper.slice(EXPORT_PREFIX.length).replace(/_\d+$/, '');
    const existing = [...functions.keys()].some((name) => name.replace(/_\d+$/, '') === base);
    if (existing) {
      const [start, end] = functions.get(wrapper);
      text = text.slice(0, start) + text.slice(end).replace(/^\n/, '');
    } else {
      text = replaceToken(text, wrapper, `${base}_0`);
    }
  }
  // Globals whose base name occurs once.
  const names = [...globalNames(text)];
  const bases = new Map();
  for (const name of names) {
    const match = /^((?:openpbr_|OpenPBR_|Enable)\w*?)_(\d+)$/.exec(name);
    if (!match) continue;
    bases.set(match[1], [...(bases.get(match[1]) ?? []), name]);
  }
  for (const [base, variants] of bases) {
    if (variants.length === 1 && !new RegExp(`\\b${base}\\b`).test(text)) text = replaceToken(text, variants[0], base);
  }
  // Struct fields: in the declarations, and after '.' (a member; swizzles carry no suffix).
  text = text.replace(/^(struct \w+\n\{\n)([\s\S]*?)(\n\};?)/gm, (whole, open, body, close) =>
    open + body.replace(/^(\s+)(\w+?)_\d+(\s*:)/gm, '$1$2$3') + close);
  text = text.replace(/\.([A-Za-z]\w*?)_\d+\b/g, '.$1');
  return text;
}

// The library's toggles as its text has them: `override` constants, or none left (every toggle
// folded by the defines, e.g. `openpbr compile --specialize`).
function toggleNote(library) {
  return /^@id\(\d+\) override /m.test(library)
    ? `// Feature toggles: the @id(N) override booleans Enable* (true by default; N as
// OPENPBR_SPECIALIZATION_ID_* of slang/openpbr_features.h), set through the pipeline's constants.`
    : `// Feature toggles: folded when generated (the defines above): no override constants; the effects
// whose OPENPBR_FEATURE_<NAME> is 0 are compiled out.`;
}

function header(options, library) {
  const specialized = options.defines.length > 0 ? options.defines.join(' ') : 'none';
  return `// openpbr.wgsl: the OpenPBR 1.1.1 surface BSDF for WebGPU (WGSL), one self-contained file generated
// from the single-source headers by targets/wgsl/generate_wgsl.mjs (Slang's WGSL target). Do not
// edit: regenerate. Defines it was generated with: ${specialized}.
//
//   let inputs = openpbr_unpack_material(material_index);         // or openpbr_make_default_resolved_inputs()
//   let bsdf = openpbr_prepare(inputs, view, openpbr_default_rgb_wavelengths_nm(), exterior_ior);
//   let f = openpbr_eval(bsdf, light);                             // BSDF x |cos|: f.diffuse + f.specular
//   let pdf = openpbr_pdf(bsdf, light);
//   let s = openpbr_sample(bsdf, u);                               // u: vec3<f32> in [0, 1)
//
// Bindings (group 0), storage buffers of f32 the application fills (README "WebGPU"):
//   @binding(0) openpbr_lut_data        slang/generated/openpbr_lut.bin (energy-compensation tables)
//   @binding(1) openpbr_fuzz_ltc_data   slang/generated/openpbr_fuzz_ltc.bin (fuzz LTC table)
//   @binding(2) openpbr_material_data   packed materials, OPENPBR_PACKED_MATERIAL_FLOATS (80) floats
//                                       each, in the order of OPENPBR_PARAMETERS (slang/openpbr_parameters.h)
${toggleNote(library)}
`;
}

function main() {
  const options = parseArgs(process.argv.slice(2));
  const appended = options.appended.map((file) => {
    try {
      return `\n// ---- ${path.basename(file)}\n${fs.readFileSync(file, 'utf8')}`;
    } catch (error) {
      throw new Error(`cannot read ${file}: ${error.message}`);
    }
  });
  const library = plainNames(slangToWgsl(options));
  const text = header(options, library) + '\n' + library + appended.join('');
  fs.mkdirSync(path.dirname(path.resolve(options.output)), { recursive: true });
  fs.writeFileSync(options.output, text);
}

try {
  main();
} catch (error) {
  console.error(`${TOOL}: error: ${error.message}`);
  process.exit(error instanceof UsageError ? 2 : 1);
}
