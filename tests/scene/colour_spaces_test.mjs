#!/usr/bin/env node
// viewer/src/colour_spaces.mjs (the viewer loader's colour conversions) reproduces
// tests/data/colour_conversions.json bit for bit, as host/scene/colour_spaces.cpp does
// (tests/scene/test_colour_spaces.cpp): the two loaders give the same working values. Also: the
// module's working space is the library's default, and viewer/display.wgsl's matrix is the
// module's working space -> display matrix. Exit status 0 when every check passes.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import {
  COLOUR_SPACE_NAMES, WORKING_SPACE, WORKING_SPACES, WORKING_TO_DISPLAY, rec709ToWorkingSpace, toWorkingSpace,
} from '../../viewer/src/colour_spaces.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const failures = [];
function check(ok, what) {
  if (!ok) failures.push(what);
}

const { cases } = JSON.parse(fs.readFileSync(path.join(root, 'tests', 'data', 'colour_conversions.json'), 'utf8'));
for (const { space, working_space: working, value, expected } of cases) {
  const converted = toWorkingSpace(space, value.map(Math.fround), working);
  check(converted !== null && converted.every((v, c) => v === Math.fround(expected[c])),
    `${space} -> ${working} of ${value}: ${converted} instead of ${expected}`);
}
check(cases.length === COLOUR_SPACE_NAMES.length * WORKING_SPACES.length * 8, `${cases.length} cases for ${COLOUR_SPACE_NAMES.length} names`);
check(toWorkingSpace('srgb', [1, 1, 1]) === null, 'an unknown name gives null');
check(rec709ToWorkingSpace([1, 1, 1]).every((v) => v === 1), 'white stays white');

// The default working space: the header's, which the viewer's kernels are compiled with.
const header = fs.readFileSync(path.join(root, 'slang', 'openpbr_working_space.h'), 'utf8');
const macro = /^\s*#\s*define\s+OPENPBR_WORKING_SPACE\s+OPENPBR_WORKING_SPACE_(\w+)\s*$/m.exec(header);
check(macro !== null && macro[1].toLowerCase() === WORKING_SPACE, `WORKING_SPACE '${WORKING_SPACE}' is the header's default (${macro?.[1]})`);

// display.wgsl's working_to_display (columns, 9 significant digits) is the module's matrix.
const wgsl = fs.readFileSync(path.join(root, 'viewer', 'display.wgsl'), 'utf8');
const numbers = /const working_to_display = mat3x3f\(([^;]*)\);/.exec(wgsl)?.[1].replace(/vec3f/g, '').match(/-?[\d.]+(?:e-?\d+)?/g).map(Number) ?? [];
const matrix = WORKING_TO_DISPLAY[WORKING_SPACE];
const columnMajor = [0, 1, 2].flatMap((column) => [0, 1, 2].map((row) => matrix[3 * row + column]));
check(numbers.length === 9 && numbers.every((v, i) => Math.abs(v - columnMajor[i]) <= 5e-9 * Math.max(1, Math.abs(v))),
  `display.wgsl's working_to_display ${numbers} is WORKING_TO_DISPLAY.${WORKING_SPACE}`);

if (failures.length > 0) {
  console.log(`${failures.length} check(s) failed:\n  ${failures.slice(0, 20).join('\n  ')}`);
  process.exit(1);
}
console.log(`colour_spaces_test: ${cases.length} conversions reproduced; working space ${WORKING_SPACE}`);
