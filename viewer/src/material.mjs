// A material as the page holds it: one value per parameter of the table, packed for the
// kernels in table order (slang/openpbr_material_packing.h).

// The parameters' defaults (a fresh copy).
export function defaultValues(table) {
  const values = {};
  for (const parameter of table.parameters) {
    if (parameter.kind === 'BASIS') continue;
    values[parameter.name] = Array.isArray(parameter.default) ? [...parameter.default] : parameter.default;
  }
  return values;
}

// The packed floats of `values` (missing entries take the table's default). Bases are packed as
// the default frame: the render kernel replaces both with the sphere's or the ground's frame at
// every hit, as openpbr render does, so the geometry_* inputs have no effect in the viewer.
export function packMaterial(table, values, packedFloats) {
  const packed = new Float32Array(packedFloats);
  for (const parameter of table.parameters) {
    const value = values[parameter.name] ?? parameter.default;
    if (parameter.kind === 'FLOAT') packed[parameter.offset] = value;
    else if (parameter.kind === 'BOOL') packed[parameter.offset] = value ? 1 : 0;
    else if (parameter.kind === 'COLOR' || parameter.kind === 'VECTOR2') packed.set(value, parameter.offset);
    else if (parameter.name === 'geometry_basis') packed.set([1, 0, 0, 0, 1, 0, 0, 0, 1], parameter.offset);
  }
  return packed;
}
