// The feature toggles of slang/openpbr_features.h, parsed from the header (OPENPBR_FEATURE_BIT_*),
// and the Slang defines that specialize a kernel to a toggle set when its WGSL is generated:
// compile-time constants (-DOPENPBR_SPECIALIZATION_CONSTANTS=0, -DOPENPBR_FEATURE_<NAME>=0 for
// each toggle off), because SwiftShader compiles a WGSL `override` only after building the whole
// kernel, and the full render kernel does not build there (toolchain-notes.md). The C++ host's
// `openpbr compile --specialize` passes the same list (host/scene/features.h,
// specialization_defines; Targets.SpecializationDefinesAreTheViewers checks that they agree).
import fs from 'node:fs';

import { codeOnly } from '../targets/source_text.mjs';

// [{ name: 'thin_film', bit: 32, define: 'OPENPBR_FEATURE_THIN_FILM' }, ...] in bit order.
export function readFeatureToggles(featuresHeader) {
  const code = codeOnly(fs.readFileSync(featuresHeader, 'utf8'));
  const toggles = [];
  for (const match of code.matchAll(/^\s*#\s*define\s+OPENPBR_FEATURE_BIT_(\w+)\s+\(1u\s*<<\s*(\d+)\)/gm)) {
    toggles.push({ name: match[1].toLowerCase(), bit: 2 ** Number(match[2]), define: `OPENPBR_FEATURE_${match[1]}` });
  }
  if (toggles.length === 0) throw new Error(`${featuresHeader}: no OPENPBR_FEATURE_BIT_* toggles`);
  return toggles.sort((a, b) => a.bit - b.bit);
}

export function fullMask(toggles) {
  return toggles.reduce((mask, toggle) => mask | toggle.bit, 0);
}

// "coat+metal", or "base" for the empty set (host/scene/features.cpp's feature_set_label).
export function featureSetLabel(toggles, mask) {
  const names = toggles.filter((toggle) => (mask & toggle.bit) !== 0).map((toggle) => toggle.name);
  return names.length > 0 ? names.join('+') : 'base';
}

// slangc.mjs -D arguments for a toggle set: every toggle outside the mask compiled out.
export function specializationDefines(toggles, mask) {
  const defines = ['OPENPBR_SPECIALIZATION_CONSTANTS=0'];
  for (const toggle of toggles) {
    if ((mask & toggle.bit) === 0) defines.push(`${toggle.define}=0`);
  }
  return defines;
}
