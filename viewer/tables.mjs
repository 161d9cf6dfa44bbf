// A table's binary form for the page: raw little-endian float32 from the tracked C-literal
// form (slang/generated/*_values.inc), the format tools/table_inc_to_bin.py writes for the
// build and the installed package (docs/tables.md): the literals carry 9 significant digits,
// so rounding each to float32 gives the generator's floats bit for bit.
import fs from 'node:fs';

export function readTableInc(file) {
  const values = [];
  fs.readFileSync(file, 'utf8').split('\n').forEach((line, index) => {
    const tokens = line.split('//', 1)[0].split(',');
    tokens.forEach((raw, position) => {
      const token = raw.trim();
      if (token === '') {
        if (position !== tokens.length - 1 && tokens.length > 1) throw new Error(`${file}:${index + 1}: empty value between commas`);
        return;
      }
      const value = Number(token.replace(/[fF]$/, ''));
      if (!Number.isFinite(value)) throw new Error(`${file}:${index + 1}: not a finite float literal: '${token}'`);
      values.push(value);
    });
  });
  if (values.length === 0) throw new Error(`${file}: no values`);
  return Buffer.from(new Float32Array(values).buffer);
}
