// Integer constants of the C-dialect headers the page shares with the kernels (buffer offsets
// of targets/kernels/openpbr_render_kernel.h, OPENPBR_PACKED_MATERIAL_FLOATS), parsed from the
// header text so that the layout is written once.
import { codeOnly } from '../../targets/source_text.mjs';

// { NAME: value } for every `#define NAME <integer>[u]` (hex included) of the text.
export function integerDefines(text) {
  const defines = {};
  for (const match of codeOnly(text).matchAll(/^\s*#\s*define\s+(\w+)\s+(0x[0-9a-fA-F]+|\d+)u?\s*$/gm)) {
    defines[match[1]] = Number(match[2]);
  }
  return defines;
}

// The value of `name`, or an error naming the header: a renamed constant must not silently
// become undefined (NaN offsets would write nothing).
export function required(defines, name, header) {
  if (!(name in defines)) throw new Error(`${header}: #define ${name} not found`);
  return defines[name];
}
