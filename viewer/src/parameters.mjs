// The OpenPBR parameter table as data, parsed from slang/openpbr_parameters.h (the one place
// the parameters are written): names, kinds, defaults and ranges for the controls, and the
// packing order of slang/openpbr_material_packing.h. Runs in the page and in Node.
import { codeOnly } from '../../targets/source_text.mjs';

// Floats each kind takes in a packed material (openpbr_material_packing.h).
const PACKED_FLOATS = { FLOAT: 1, COLOR: 3, VECTOR2: 2, BOOL: 1, BASIS: 9 };

// A float literal of the table ("0.8f", "1e18f") or one of the header's own #define bounds.
function evaluate(token, constants) {
  const text = token.trim();
  if (text in constants) return constants[text];
  const literal = text.replace(/[fF]$/, '');
  const value = Number(literal);
  if (literal === '' || !Number.isFinite(value)) throw new Error(`openpbr_parameters.h: cannot read '${text}'`);
  return Math.fround(value);
}

function parseBool(token) {
  const text = token.trim();
  if (text !== 'true' && text !== 'false') throw new Error(`openpbr_parameters.h: '${text}' is not a bool`);
  return text === 'true';
}

// Parses the header text into { parameters, packedFloats }. Each parameter: { kind, name,
// offset (packing slot), default (number, [r, g, b], [x, y] or bool), low, high } and for a
// BASIS { normalInput, tangentInput }.
export function parseParameterTable(headerText) {
  const code = codeOnly(headerText);
  const constants = {};
  for (const match of code.matchAll(/^\s*#\s*define\s+(OPENPBR_\w+)\s+([-+\d.eE]+f?)\s*$/gm)) {
    constants[match[1]] = evaluate(match[2], {});
  }
  const body = /#\s*define\s+OPENPBR_PARAMETERS\s*\([^)]*\)([\s\S]*?)(?:\n\s*\n|\n\s*#)/.exec(code);
  if (!body) throw new Error('openpbr_parameters.h: no OPENPBR_PARAMETERS table');
  const parameters = [];
  let offset = 0;
  for (const match of body[1].matchAll(/\b(FLOAT|COLOR|VECTOR2|BOOL|BASIS)\s*\(([^)]*)\)/g)) {
    const kind = match[1];
    const args = match[2].split(',').map((arg) => arg.trim());
    const name = args[0];
    const entry = { kind, name, offset };
    if (kind === 'FLOAT') {
      entry.default = evaluate(args[1], constants);
      entry.low = evaluate(args[2], constants);
      entry.high = evaluate(args[3], constants);
    } else if (kind === 'COLOR') {
      entry.default = args.slice(1, 4).map((arg) => evaluate(arg, constants));
      entry.low = evaluate(args[4], constants);
      entry.high = evaluate(args[5], constants);
    } else if (kind === 'VECTOR2') {
      entry.default = args.slice(1, 3).map((arg) => evaluate(arg, constants));
    } else if (kind === 'BOOL') {
      entry.default = parseBool(args[1]);
    } else {
      entry.normalInput = args[1];
      entry.tangentInput = args[2];
    }
    parameters.push(entry);
    offset += PACKED_FLOATS[kind];
  }
  if (parameters.length === 0) throw new Error('openpbr_parameters.h: the table is empty');
  return { parameters, packedFloats: offset };
}

// The MaterialX inputs of the table, as host/scene/parameter_table.cpp lists them: a FLOAT,
// COLOR or BOOL under its own name (types float, color3, boolean), a BASIS as its two vector3
// inputs; VECTOR2 extensions have none. Map from input name to { parameter, type, role }.
export function materialxInputs(parameters) {
  const inputs = new Map();
  const types = { FLOAT: 'float', COLOR: 'color3', BOOL: 'boolean' };
  for (const parameter of parameters) {
    if (parameter.kind === 'BASIS') {
      inputs.set(parameter.normalInput, { parameter, type: 'vector3', role: 'normal' });
      inputs.set(parameter.tangentInput, { parameter, type: 'vector3', role: 'tangent' });
    } else if (parameter.kind in types) {
      inputs.set(parameter.name, { parameter, type: types[parameter.kind] });
    }
  }
  return inputs;
}
