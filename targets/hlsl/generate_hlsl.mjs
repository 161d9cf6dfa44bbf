#!/usr/bin/env node
// generate_hlsl.mjs: flattens the single-source headers into one self-contained HLSL file.
//
//   node targets/hlsl/generate_hlsl.mjs [-preset hlsl] [-I DIR]... [-D NAME[=V]]... [-U NAME]...
//        [-provided FILE]... [-o OUT] INPUT
// e.g. (what `openpbr compile --target hlsl` runs):
//   node targets/hlsl/generate_hlsl.mjs -preset hlsl -I slang -o openpbr.hlsl targets/hlsl/openpbr.hlsl.in
//   node targets/hlsl/generate_hlsl.mjs -preset hlsl -I slang -provided targets/hlsl/openpbr.hlsl.in \
//        -o openpbr_conformance_kernel.hlsl targets/kernels/openpbr_conformance_kernel.h
//
// 1. Includes (`#include "x"`: the including file's directory, then -I) are inlined, each
//    file once; a file that -provided FILE would inline is assumed present already (its
//    include line is dropped): e.g. a kernel generated next to openpbr.hlsl.
// 2. In the inlined files (not in INPUT itself, whose directives stay as written),
//    conditionals on the -D / -U symbols are resolved like unifdef does: branches that
//    cannot be taken are dropped with their directives, and conditionals on other symbols
//    stay. An include under such a remaining conditional (other than an include guard) is an
//    error, since inlining it once could be wrong.
// 3. The GLSL dialect is spelled in HLSL: vec2/3/4 -> float2/3/4, mix -> lerp, fract -> frac,
//    inversesqrt -> rsqrt, and a vector built from one value, vec3(x), -> openpbr_splat3(x)
//    (DXC and FXC reject float3(x)); the backend's #define lines for those names are dropped,
//    so the output defines none of them in the includer's scope.
// Comments are kept; each inlined file is marked with a comment naming it.
import fs from 'node:fs';
import path from 'node:path';

import { codeOfLine } from '../source_text.mjs';

const TOOL = 'generate_hlsl.mjs';
const DIALECT = { vec2: 'float2', vec3: 'float3', vec4: 'float4', mix: 'lerp', fract: 'frac', inversesqrt: 'rsqrt' };
const SPLAT = { vec2: 'openpbr_splat2', vec3: 'openpbr_splat3', vec4: 'openpbr_splat4' };

// -preset hlsl: the language is HLSL, no other language or compiler macro is defined, and the
// tables have no array mode (openpbr.hlsl.in rejects it).
const PRESETS = {
  hlsl: [
    ['OPENPBR_LANGUAGE_TARGET_HLSL', 1],
    // The generated file is the whole interop layer, spelled in HLSL: no host hooks for it.
    ['OPENPBR_USE_CUSTOM_INTEROP', 0],
    ['OPENPBR_USE_CUSTOM_VEC_TYPES', 0],
    ...['OPENPBR_LANGUAGE_TARGET_SLANG', 'OPENPBR_LANGUAGE_TARGET_GLSL', 'OPENPBR_LANGUAGE_TARGET_CPP',
      'OPENPBR_LANGUAGE_TARGET_CUDA', 'OPENPBR_LANGUAGE_TARGET_METAL', 'OPENPBR_LANGUAGE_TARGET_MSL', 'OPENPBR_LUT_MODE_ARRAY',
      'OPENPBR_FUZZ_LTC_MODE_ARRAY', '__cplusplus', '__CUDACC__', '__CUDA_ARCH__', '__METAL_VERSION__',
    ].map((name) => [name, null]),
  ],
};

class GenerateError extends Error {}

function parseArgs(argv) {
  const opts = { includeDirs: [], known: new Map(), provided: [], output: null, input: null };
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) throw new GenerateError(`${arg} needs a value`);
      return argv[++i];
    };
    const glued = /^-([DIU])(.+)$/.exec(arg);
    const flag = glued ? `-${glued[1]}` : arg;
    const take = () => (glued ? glued[2] : value());
    switch (flag) {
      case '-I': opts.includeDirs.push(take()); break;
      case '-D': {
        const def = take();
        const eq = def.indexOf('=');
        opts.known.set(eq < 0 ? def : def.slice(0, eq), eq < 0 ? 1 : Number(def.slice(eq + 1)));
        break;
      }
      case '-U': opts.known.set(take(), null); break;
      case '-provided': opts.provided.push(value()); break;
      case '-preset': {
        const preset = PRESETS[value()];
        if (!preset) throw new GenerateError(`unknown preset; known: ${Object.keys(PRESETS).join(', ')}`);
        for (const [name, v] of preset) opts.known.set(name, v);
        break;
      }
      case '-o': opts.output = value(); break;
      default:
        if (arg.startsWith('-')) throw new GenerateError(`unknown option ${arg}`);
        if (opts.input) throw new GenerateError('one input file only');
        opts.input = arg;
    }
  }
  if (!opts.input) throw new GenerateError('no input file');
  return opts;
}

// ---------------------------------------------------------------------------------------------
// Lines: physical lines grouped into logical lines (backslash continuations), with the code of
// each (comments removed) for directive parsing.

function logicalLines(text) {
  const physical = text.split(/\r?\n/);
  const result = [];
  let inBlock = false;
  for (let i = 0; i < physical.length; i++) {
    const start = i;
    let code = '';
    for (;;) {
      const stripped = codeOfLine(physical[i], inBlock);
      inBlock = stripped.inBlock;
      code += stripped.code;
      if (physical[i].endsWith('\\') && i + 1 < physical.length) {
        code = code.replace(/\\$/, ' ');
        i++;
        continue;
      }
      break;
    }
    result.push({ lines: physical.slice(start, i + 1), code, number: start + 1 });
  }
  return result;
}

const DIRECTIVE_RE = /^\s*#\s*(\w+)\s*(.*)$/;

// ---------------------------------------------------------------------------------------------
// #if expressions with three-valued logic: a number, or null when it depends on a symbol
// the command line does not fix.

function evaluate(expression, known) {
  const tokens = expression.match(/\d+[uUlL]*|\w+|&&|\|\||==|!=|<=|>=|<<|>>|[-+*/%<>!~&|^()?:,]/g) ?? [];
  let pos = 0;
  const peek = () => tokens[pos];
  const next = () => tokens[pos++];
  const expect = (t) => {
    if (next() !== t) throw new GenerateError(`cannot parse #if ${expression}`);
  };
  const unknown = null;
  const binary = (a, b, fn) => (a === unknown || b === unknown ? unknown : fn(a, b));

  function primary() {
    const t = next();
    if (t === undefined) throw new GenerateError(`cannot parse #if ${expression}`);
    if (t === '(') {
      const v = conditional();
      expect(')');
      return v;
    }
    if (t === '!') { const v = primary(); return v === unknown ? unknown : Number(!v); }
    if (t === '-') { const v = primary(); return v === unknown ? unknown : -v; }
    if (t === '+') return primary();
    if (t === '~') { const v = primary(); return v === unknown ? unknown : ~v; }
    if (t === 'defined') {
      const paren = peek() === '(';
      if (paren) next();
      const name = next();
      if (paren) expect(')');
      if (!known.has(name)) return unknown;
      return known.get(name) === null ? 0 : 1;
    }
    if (/^\d/.test(t)) return Number.parseInt(t, 10);
    if (/^\w+$/.test(t)) {
      // A function-like macro call: its value is not known here.
      if (peek() === '(') {
        let depth = 0;
        do {
          const u = next();
          if (u === '(') depth++;
          else if (u === ')') depth--;
          else if (u === undefined) throw new GenerateError(`cannot parse #if ${expression}`);
        } while (depth > 0);
        return unknown;
      }
      if (known.has(t)) return known.get(t) ?? 0;
      return unknown;
    }
    throw new GenerateError(`cannot parse #if ${expression}`);
  }
  const LEVELS = [
    ['*', '/', '%'], ['+', '-'], ['<<', '>>'], ['<', '>', '<=', '>='], ['==', '!='], ['&'], ['^'], ['|'],
  ];
  const OPS = {
    '*': (a, b) => a * b, '/': (a, b) => Math.trunc(a / b), '%': (a, b) => a % b, '+': (a, b) => a + b,
    '-': (a, b) => a - b, '<<': (a, b) => a << b, '>>': (a, b) => a >> b, '<': (a, b) => Number(a < b),
    '>': (a, b) => Number(a > b), '<=': (a, b) => Number(a <= b), '>=': (a, b) => Number(a >= b),
    '==': (a, b) => Number(a === b), '!=': (a, b) => Number(a !== b), '&': (a, b) => a & b,
    '^': (a, b) => a ^ b, '|': (a, b) => a | b,
  };
  function level(n) {
    if (n < 0) return primary();
    let v = level(n - 1);
    while (LEVELS[n].includes(peek())) {
      const op = next();
      v = binary(v, level(n - 1), OPS[op]);
    }
    return v;
  }
  function logicalAnd() {
    let v = level(LEVELS.length - 1);
    while (peek() === '&&') {
      next();
      const w = level(LEVELS.length - 1);
      v = v === 0 || w === 0 ? 0 : v === unknown || w === unknown ? unknown : 1;
    }
    return v;
  }
  function logicalOr() {
    let v = logicalAnd();
    while (peek() === '||') {
      next();
      const w = logicalAnd();
      const truthy = (x) => x !== unknown && x !== 0;
      v = truthy(v) || truthy(w) ? 1 : v === unknown || w === unknown ? unknown : 0;
    }
    return v;
  }
  function conditional() {
    const c = logicalOr();
    if (peek() !== '?') return c;
    next();
    const a = conditional();
    expect(':');
    const b = conditional();
    if (c === unknown) return a === b ? a : unknown;
    return c ? a : b;
  }
  const value = conditional();
  if (pos !== tokens.length) throw new GenerateError(`cannot parse #if ${expression}`);
  return value;
}

// ---------------------------------------------------------------------------------------------
// Flattening

function findInclude(name, current, includeDirs) {
  for (const dir of [path.dirname(current), ...includeDirs]) {
    const candidate = path.join(dir, name);
    if (fs.existsSync(candidate) && fs.statSync(candidate).isFile()) return candidate;
  }
  return null;
}

function readSource(file) {
  try {
    return fs.readFileSync(file, 'utf8');
  } catch (err) {
    throw new GenerateError(`cannot read '${file}': ${err.message}`);
  }
}

// Index of the logical line that opens a classic include guard, or -1.
function guardIndex(lines) {
  const code = lines.map((l, index) => ({ code: l.code.trim(), index })).filter((l) => l.code !== '');
  const first = code[0] && /^#\s*ifndef\s+(\w+)$/.exec(code[0].code);
  if (!first || !code[1]) return -1;
  return new RegExp(`^#\\s*define\\s+${first[1]}\\b`).test(code[1].code) ? code[0].index : -1;
}

function flatten(input, opts, provided) {
  const root = path.resolve(input);
  const seen = new Set(provided);
  const files = [];
  const out = [];

  function expand(file, resolve) {
    const real = fs.realpathSync(file);
    seen.add(real);
    files.push(real);
    const lines = logicalLines(readSource(file));
    const guard = guardIndex(lines);
    // Each open conditional: { kept: directive stays, taken: a branch was taken for sure,
    // active: the current branch may be compiled, guard: the file's include guard }.
    const stack = [];
    const active = () => stack.every((c) => c.active);
    const keptNonGuard = () => stack.some((c) => c.kept && !c.guard && c.active);
    lines.forEach((line, index) => {
      const directive = DIRECTIVE_RE.exec(line.code);
      const emit = (text) => { if (active()) out.push(...(text ?? line.lines)); };
      if (!directive) {
        emit();
        return;
      }
      const [, name, rest] = directive;
      const conditionValue = (expr) => (resolve ? evaluate(expr, opts.known) : null);
      switch (name) {
        case 'if': case 'ifdef': case 'ifndef': {
          const parentActive = active();
          let value;
          if (name === 'if') value = conditionValue(rest);
          else {
            const symbol = rest.trim().split(/\s+/)[0];
            value = resolve && opts.known.has(symbol) ? Number((opts.known.get(symbol) !== null) === (name === 'ifdef')) : null;
          }
          const entry = { kept: false, taken: false, active: false, guard: index === guard, everKept: false };
          if (value === null) {
            entry.kept = true; entry.everKept = true; entry.active = true;
            if (parentActive) out.push(...line.lines);
          } else {
            entry.active = value !== 0;
            entry.taken = value !== 0;
          }
          stack.push(entry);
          return;
        }
        case 'elif': case 'else': {
          const entry = stack[stack.length - 1];
          if (!entry) throw new GenerateError(`${file}:${line.number}: #${name} without #if`);
          stack.pop();
          const parentActive = active();
          stack.push(entry);
          if (entry.taken) {
            entry.active = false;
            return;
          }
          const value = name === 'else' ? 1 : conditionValue(rest);
          if (value === 0) {
            entry.active = false;
            return;
          }
          if (value === null) {
            if (parentActive) out.push(...(entry.kept ? line.lines : [line.lines[0].replace(/#\s*elif/, '#if')]));
            entry.kept = true; entry.everKept = true; entry.active = true;
            return;
          }
          // Certainly taken: after kept branches it is their #else; alone, its text stays bare.
          if (entry.kept && parentActive) out.push(line.lines[0].replace(/#\s*elif.*/, '#else'));
          entry.kept = entry.kept || false;
          entry.taken = true;
          entry.active = true;
          return;
        }
        case 'endif': {
          const entry = stack.pop();
          if (!entry) throw new GenerateError(`${file}:${line.number}: #endif without #if`);
          if (entry.everKept && active()) out.push(...line.lines);
          return;
        }
        case 'pragma':
          if (/^once\b/.test(rest.trim())) return;
          emit();
          return;
        case 'define': {
          const macro = /^(\w+)/.exec(rest)?.[1];
          // The backend's dialect macros: the output spells those names in HLSL instead.
          if (resolve && macro && Object.hasOwn(DIALECT, macro)) return;
          emit();
          return;
        }
        case 'include': {
          if (!active()) return;
          const quoted = /^"([^"]+)"/.exec(rest.trim());
          const found = quoted && findInclude(quoted[1], file, opts.includeDirs);
          if (!found) {
            emit();
            return;
          }
          const foundReal = fs.realpathSync(found);
          if (seen.has(foundReal)) {
            out.push(`// (${displayPath(found)}: already included)`);
            return;
          }
          if (keptNonGuard()) {
            throw new GenerateError(`${file}:${line.number}: include of ${quoted[1]} under a conditional that `
              + 'depends on symbols not given with -D/-U; cannot inline it once');
          }
          out.push(`// ---- begin ${displayPath(found)} ----`);
          expand(found, true);
          out.push(`// ---- end ${displayPath(found)} ----`);
          return;
        }
        default:
          emit();
      }
    });
    if (stack.length) throw new GenerateError(`${file}: unterminated #if`);
  }

  expand(root, false);
  return { text: out.join('\n'), files };
}

// Names in the marker comments: relative to the parent of the first -I directory (the
// repository root for -I slang), so the output does not depend on the working directory.
let displayRoot = null;
function displayPath(file) {
  const relative = path.relative(displayRoot ?? process.cwd(), file);
  return relative.startsWith('..') ? path.basename(file) : relative.split(path.sep).join('/');
}

// ---------------------------------------------------------------------------------------------
// Dialect -> HLSL, on code only (comments and string literals are left alone).

function rewriteDialect(text) {
  let result = '';
  let i = 0;
  const n = text.length;
  while (i < n) {
    const c = text[i];
    if (text.startsWith('//', i)) {
      const end = text.indexOf('\n', i);
      const stop = end < 0 ? n : end;
      result += text.slice(i, stop);
      i = stop;
    } else if (text.startsWith('/*', i)) {
      const end = text.indexOf('*/', i + 2);
      const stop = end < 0 ? n : end + 2;
      result += text.slice(i, stop);
      i = stop;
    } else if (c === '"') {
      let j = i + 1;
      while (j < n && text[j] !== '"' && text[j] !== '\n') j += text[j] === '\\' ? 2 : 1;
      result += text.slice(i, j + 1);
      i = j + 1;
    } else if (/[A-Za-z_]/.test(c)) {
      let j = i;
      while (j < n && /\w/.test(text[j])) j++;
      const word = text.slice(i, j);
      if (Object.hasOwn(SPLAT, word) && singleArgumentCall(text, j)) result += SPLAT[word];
      else result += Object.hasOwn(DIALECT, word) ? DIALECT[word] : word;
      i = j;
    } else if (/\d/.test(c)) {
      // Numbers whole, so that 1e3f is not read as identifier e3f.
      let j = i;
      while (j < n && /[\w.]/.test(text[j])) j++;
      result += text.slice(i, j);
      i = j;
    } else {
      result += c;
      i++;
    }
  }
  return result;
}

// True when text[from..] is `( one argument )`: no comma at the top nesting level.
function singleArgumentCall(text, from) {
  let i = from;
  while (i < text.length && /[ \t]/.test(text[i])) i++;
  if (text[i] !== '(') return false;
  let depth = 0;
  let empty = true;
  for (; i < text.length; i++) {
    const c = text[i];
    if (c === '(' || c === '[' || c === '{') depth++;
    else if (c === ')' || c === ']' || c === '}') {
      depth--;
      if (depth === 0) return !empty;
    } else if (c === ',' && depth === 1) return false;
    else if (!/\s/.test(c)) empty = false;
  }
  return false;
}

// ---------------------------------------------------------------------------------------------

function main(argv) {
  const opts = parseArgs(argv);
  if (opts.includeDirs.length) displayRoot = path.dirname(path.resolve(opts.includeDirs[0]));
  const provided = new Set();
  for (const file of opts.provided) {
    for (const f of flatten(file, opts, []).files) provided.add(f);
  }
  const { text } = flatten(opts.input, opts, provided);
  const hlsl = `${rewriteDialect(text).replace(/\n{3,}/g, '\n\n').trimEnd()}\n`;
  if (opts.output) {
    fs.mkdirSync(path.dirname(path.resolve(opts.output)), { recursive: true });
    fs.writeFileSync(opts.output, hlsl);
  } else {
    process.stdout.write(hlsl);
  }
}

try {
  main(process.argv.slice(2));
} catch (err) {
  if (!(err instanceof GenerateError)) throw err;
  console.error(`${TOOL}: error: ${err.message}`);
  process.exit(1);
}
