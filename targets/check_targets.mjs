#!/usr/bin/env node
// check_targets.mjs: checks on generated shader text that no compiler on this machine makes.
//
//   node targets/check_targets.mjs hlsl-library FILE
//       The self-contained openpbr.hlsl: no #include left, no [[vk::...]] attribute, no name of
//       the GLSL dialect, no vector constructor from one value (float3(x): DXC and FXC reject
//       it, glslang accepts it, so glslang cannot catch it), no long constant array, only
//       OPENPBR_-prefixed macros, the API and the two table buffers present.
//   node targets/check_targets.mjs metal FILE ENTRY SOURCE...
//       Slang's Metal output (not compiled on Linux): the [[kernel]] entry point is present, one
//       [[function_constant(N)]] per [vk::constant_id(N)] of the SOURCE files, no constant
//       array, and no two kernel arguments share a [[buffer(N)]] index.
// Prints "ok: ..." per passed check and "FAIL: ..." per failure; exit status 1 on any failure.
import fs from 'node:fs';

import { codeOnly } from './source_text.mjs';

let failures = 0;
const ok = (what) => console.log(`ok:   ${what}`);
const fail = (what) => { console.log(`FAIL: ${what}`); failures++; };
const check = (condition, what, detail = '') => (condition ? ok(what) : fail(detail ? `${what}: ${detail}` : what));

function lineOf(text, index) {
  return text.slice(0, index).split('\n').length;
}

// Calls name(...) whose argument list has one top-level argument; returns their line numbers.
function singleArgumentCalls(code, namePattern) {
  const lines = [];
  const re = new RegExp(`\\b(${namePattern})\\s*\\(`, 'g');
  for (const match of code.matchAll(re)) {
    let depth = 0;
    let commas = 0;
    let i = match.index + match[0].length - 1;
    for (; i < code.length; i++) {
      const c = code[i];
      if ('([{'.includes(c)) depth++;
      else if (')]}'.includes(c)) {
        depth--;
        if (depth === 0) break;
      } else if (c === ',' && depth === 1) commas++;
    }
    const inside = code.slice(match.index + match[0].length, i).trim();
    if (commas === 0 && inside !== '') lines.push(lineOf(code, match.index));
  }
  return lines;
}

// Brace initializer lists with more than `limit` elements: long constant arrays.
function longInitializers(code, limit) {
  const found = [];
  for (const match of code.matchAll(/=\s*\{([^{}]*)\}/g)) {
    const count = match[1].split(',').filter((s) => s.trim() !== '').length;
    if (count > limit) found.push(`line ${lineOf(code, match.index)} (${count} elements)`);
  }
  return found;
}

function checkHlslLibrary(file) {
  const text = fs.readFileSync(file, 'utf8');
  const code = codeOnly(text);
  const includes = [...code.matchAll(/^\s*#\s*include\b.*$/gm)].map((m) => m[0].trim());
  check(includes.length === 0, 'self-contained (no #include)', includes.join('; '));
  check(!/\[\[\s*vk::/.test(code), 'no [[vk::...]] attributes (DXIL and FXC builds)');
  const dialect = [...code.matchAll(/\b(vec[234]|[iub]vec[234]|mat[234]|mix|fract|inversesqrt|mod)\b/g)]
    .map((m) => `${m[1]} (line ${lineOf(code, m.index)})`);
  check(dialect.length === 0, 'no GLSL dialect names left', dialect.slice(0, 5).join(', '));
  const splats = singleArgumentCalls(code, '(?:float|int|uint|bool|half|double)[234]');
  check(splats.length === 0, 'no vector constructor from one value (DXC: "too few elements")',
    `lines ${splats.slice(0, 10).join(', ')}`);
  const long = longInitializers(code, 64);
  check(long.length === 0, 'no long constant arrays', long.join(', '));
  const macros = [...code.matchAll(/^\s*#\s*define\s+(\w+)/gm)].map((m) => m[1])
    .filter((name) => !name.startsWith('OPENPBR_') && !name.startsWith('OpenPBR_'));
  check(macros.length === 0, 'defines only OPENPBR_* / OpenPBR_* macros', macros.join(', '));
  for (const name of ['openpbr_prepare', 'openpbr_eval', 'openpbr_sample', 'openpbr_pdf', 'openpbr_unpack_material']) {
    check(new RegExp(`\\b${name}\\s*\\(`).test(code), `function ${name}`);
  }
  for (const name of ['OpenPBR_ResolvedInputs', 'OpenPBR_PreparedBsdf', 'OpenPBR_BsdfSample', 'OpenPBR_DiffuseSpecular']) {
    check(new RegExp(`\\bstruct\\s+${name}\\b`).test(code), `struct ${name}`);
  }
  for (const [name, binding] of [['openpbr_lut_data', 'OPENPBR_LUT_BINDING'], ['openpbr_fuzz_ltc_data', 'OPENPBR_FUZZ_LTC_BINDING']]) {
    check(new RegExp(`StructuredBuffer<float>\\s+${name}\\s*:\\s*register\\(OPENPBR_CONCATENATE\\(t,\\s*${binding}\\)`).test(code),
      `table ${name}: StructuredBuffer<float> at register t<${binding}>`);
  }
}

function checkMetal(file, entry, sources) {
  const text = fs.readFileSync(file, 'utf8');
  const code = codeOnly(text);
  const head = new RegExp(`\\[\\[kernel\\]\\]\\s*void\\s+${entry}\\s*\\(`).exec(code);
  check(Boolean(head), `entry point [[kernel]] void ${entry}(...)`);
  let kernel = null;
  if (head) {
    // The argument list, up to the parenthesis that closes it.
    let depth = 1;
    let i = head.index + head[0].length;
    for (; i < code.length && depth > 0; i++) {
      if (code[i] === '(') depth++;
      else if (code[i] === ')') depth--;
    }
    kernel = [null, code.slice(head.index + head[0].length, i - 1)];
  }
  const wanted = new Set();
  for (const source of sources) {
    for (const m of codeOnly(fs.readFileSync(source, 'utf8')).matchAll(/\[\s*vk::constant_id\s*\(\s*(\d+)\s*\)\s*\]/g)) {
      wanted.add(Number(m[1]));
    }
    // The feature toggles declare theirs through a macro, with the ids defined as
    // OPENPBR_SPECIALIZATION_ID_<name> (slang/openpbr_features.h).
    for (const m of codeOnly(fs.readFileSync(source, 'utf8')).matchAll(/#\s*define\s+OPENPBR_SPECIALIZATION_ID_\w+\s+(\d+)/g)) {
      wanted.add(Number(m[1]));
    }
  }
  const found = [...code.matchAll(/\[\[\s*function_constant\s*\(\s*(\d+)\s*\)\s*\]\]/g)].map((m) => Number(m[1]));
  const counts = new Map();
  for (const id of found) counts.set(id, (counts.get(id) ?? 0) + 1);
  const ids = [...wanted].sort((a, b) => a - b);
  check(ids.every((id) => counts.get(id) === 1) && found.length === ids.length,
    `one [[function_constant(N)]] per specialization constant (${ids.length ? ids.join(', ') : 'none'})`,
    `found ${JSON.stringify([...counts])}`);
  const arrays = [...code.matchAll(/\bconstant\s+[\w:<>]+\s+\w+\s*\[\s*\d+\s*\]/g)].map((m) => `line ${lineOf(code, m.index)}`);
  check(arrays.length === 0, 'no constant arrays', arrays.slice(0, 5).join(', '));
  const long = longInitializers(code, 64);
  check(long.length === 0, 'no long array initializers', long.join(', '));
  if (kernel) {
    const indices = [...kernel[1].matchAll(/\[\[\s*buffer\s*\(\s*(\d+)\s*\)\s*\]\]/g)].map((m) => Number(m[1]));
    const duplicates = indices.filter((v, i) => indices.indexOf(v) !== i);
    check(duplicates.length === 0, `kernel arguments have distinct [[buffer(N)]] indices (${indices.join(', ')})`,
      `index ${[...new Set(duplicates)].join(', ')} used twice (a t and a u register with one number?)`);
  }
}

const [command, ...args] = process.argv.slice(2);
if (command === 'hlsl-library' && args.length === 1) checkHlslLibrary(args[0]);
else if (command === 'metal' && args.length >= 3) checkMetal(args[0], args[1], args.slice(2));
else {
  console.error('usage: check_targets.mjs hlsl-library FILE | metal FILE ENTRY SOURCE...');
  process.exit(2);
}
process.exit(failures ? 1 : 0);
