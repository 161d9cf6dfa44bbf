// MaterialX reader for constant-valued <open_pbr_surface> nodes, with the rules of the C++
// loader (host/scene/material_library.cpp), so a file loads here exactly when `openpbr render
// --materials` loads it, with the same values: inputs are the parameter table's MaterialX
// inputs (parameters.mjs materialxInputs), each given once, of the table's type, with a
// constant value (no connections); numbers are comma-separated finite float32 values; booleans
// 'true' or 'false'. color3 values are converted from their colour space (the input's
// colorspace, else the document's, else acescg) into the working space (colour_spaces.mjs, the
// C++ loader's table); an unknown colour space is an error. An open_pbr_surface may name its
// version: 1.1 and 1.1.1 are read. Each <surfacematerial> whose surfaceshader is an
// open_pbr_surface is a material (named after it), then each open_pbr_surface no material
// references (named after the node). Errors throw MaterialError with a location.
import { COLOUR_SPACE_NAMES, DEFAULT_DOCUMENT_SPACE, toWorkingSpace } from './colour_spaces.mjs';
import { materialxInputs } from './parameters.mjs';

export class MaterialError extends Error {}

const CONNECTION_ATTRIBUTES = ['nodename', 'nodegraph', 'output', 'interfacename'];
const SUPPORTED_VERSIONS = ['1.1', '1.1.1'];

function unknownColorspace(name) {
  return `unknown colorspace '${name}' (known: ${COLOUR_SPACE_NAMES.join(', ')})`;
}

// What std::from_chars accepts as a float in the C++ reader: an optional '-', digits with an
// optional fraction (or a fraction alone), an optional exponent; a leading '+' is dropped first.
const NUMBER_RE = /^-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?$/;
const NON_FINITE_RE = /^-?(?:inf|infinity|nan(?:\([\w]*\))?)$/i;
const FLOAT_MAX = 3.4028234663852886e38;

function where(file, element) {
  return `${file}: <${element.tagName} name="${element.getAttribute('name') ?? ''}">`;
}

// Parses "0.8, 0.8, 0.8" into float32 values, or returns an error description.
function parseFloatList(text) {
  const values = [];
  for (const raw of text.split(',')) {
    const piece = raw.trim();
    const number = piece.startsWith('+') ? piece.slice(1) : piece;
    if (NON_FINITE_RE.test(number)) return { problem: `non-finite value '${piece}'` };
    if (!NUMBER_RE.test(number)) return { problem: `cannot parse '${piece}' as a number` };
    const value = Number(number);
    if (Math.abs(value) > FLOAT_MAX) return { problem: `'${piece}' is outside the range of a 32-bit float` };
    values.push(Math.fround(value));
  }
  return { values };
}

function readInput(file, colorspace, surface, input, inputs, values, seen) {
  const name = input.getAttribute('name') ?? '';
  const surfaceName = surface.getAttribute('name') ?? '';
  const context = `open_pbr_surface '${surfaceName}', input '${name}'`;
  const fail = (problem) => { throw new MaterialError(`${where(file, input)}: ${problem}`); };
  if (name === '') fail(`open_pbr_surface '${surfaceName}' has an <input> without a name`);
  const known = inputs.get(name);
  if (!known) fail(`${context}: unknown input name (not an OpenPBR 1.1.1 input)`);
  if (seen.has(name)) fail(`${context}: input given more than once`);
  for (const attribute of CONNECTION_ATTRIBUTES) {
    if (input.hasAttribute(attribute)) {
      fail(`${context}: connected input (${attribute}="${input.getAttribute(attribute)}"); textures and node graphs are not supported, only constant values`);
    }
  }
  const type = input.getAttribute('type');
  if (type === null) fail(`${context}: missing type attribute (expected '${known.type}')`);
  if (type !== known.type) fail(`${context}: wrong type '${type}', expected '${known.type}'`);
  // An input's own colorspace overrides the document's; only color3 values are converted.
  const inputColorspace = input.getAttribute('colorspace');
  const space = inputColorspace ?? colorspace;
  if (inputColorspace !== null && toWorkingSpace(space, [0, 0, 0]) === null) fail(`${context}: ${unknownColorspace(space)}`);
  const text = input.getAttribute('value');
  if (text === null) fail(`${context}: no value attribute`);
  let value;
  if (known.type === 'boolean') {
    const word = text.trim();
    if (word !== 'true' && word !== 'false') fail(`${context}: boolean value must be 'true' or 'false', got '${text}'`);
    value = word === 'true';
  } else {
    const { values: components, problem } = parseFloatList(text);
    if (problem) fail(`${context}: ${problem} in value '${text}'`);
    const expected = known.type === 'float' ? 1 : 3;
    if (components.length !== expected) {
      fail(`${context}: value '${text}' has ${components.length} component(s), type '${known.type}' needs ${expected}`);
    }
    value = expected === 1 ? components[0] : components;
    if (known.type === 'color3') value = toWorkingSpace(space, components);
  }
  seen.add(name);
  // geometry_* vectors are checked but not stored: the render kernel sets the frame per hit.
  if (known.type !== 'vector3') values[name] = value;
}

function readSurface(file, colorspace, surface, materialName, inputs) {
  const version = surface.getAttribute('version');
  if (version !== null && !SUPPORTED_VERSIONS.includes(version)) {
    throw new MaterialError(`${where(file, surface)}: open_pbr_surface '${surface.getAttribute('name') ?? ''}': version '${version}' is not supported (this loader reads OpenPBR 1.1 and 1.1.1)`);
  }
  const values = {};
  const seen = new Set();
  for (const input of surface.children) {
    if (input.tagName === 'input') readInput(file, colorspace, surface, input, inputs, values, seen);
  }
  return { name: materialName, file, values, inputsSet: [...seen] };
}

// The materials of one .mtlx text: [{ name, file, values: { parameter: value }, inputsSet }].
export function parseMaterialX(text, file, table, parser = new DOMParser()) {
  const document = parser.parseFromString(text, 'application/xml');
  const error = document.getElementsByTagName('parsererror')[0];
  // Chromium puts the parser's message in a <div> of the <parsererror>; other browsers in its text.
  if (error) throw new MaterialError(`${file}: malformed XML: ${(error.querySelector('div') ?? error).textContent.trim().split('\n')[0]}`);
  const root = document.documentElement;
  if (root.tagName !== 'materialx') {
    throw new MaterialError(`${file}: not a MaterialX document (root element is <${root.tagName}>, expected <materialx>)`);
  }
  const inputs = materialxInputs(table.parameters);
  // No colorspace on the document: the specification's default, ACEScg ("Metadata").
  const colorspace = root.getAttribute('colorspace') ?? DEFAULT_DOCUMENT_SPACE;
  if (toWorkingSpace(colorspace, [0, 0, 0]) === null) throw new MaterialError(`${file}: <materialx>: ${unknownColorspace(colorspace)}`);
  const topLevel = new Map();
  for (const element of root.children) {
    const name = element.getAttribute('name') ?? '';
    if (name === '') continue;
    if (topLevel.has(name)) throw new MaterialError(`${where(file, element)}: duplicate element name '${name}'`);
    topLevel.set(name, element);
  }
  const materials = [];
  const referenced = new Set();
  for (const material of root.children) {
    if (material.tagName !== 'surfacematerial') continue;
    const materialName = material.getAttribute('name') ?? '';
    const context = `surfacematerial '${materialName}'`;
    const shader = [...material.children].find((child) => child.tagName === 'input' && child.getAttribute('name') === 'surfaceshader');
    if (!shader) throw new MaterialError(`${where(file, material)}: ${context}: no surfaceshader input`);
    if (shader.hasAttribute('nodegraph')) {
      throw new MaterialError(`${where(file, shader)}: ${context}: surfaceshader connected to nodegraph '${shader.getAttribute('nodegraph')}'; node graphs are not supported`);
    }
    const nodeName = shader.getAttribute('nodename') ?? '';
    if (nodeName === '') throw new MaterialError(`${where(file, shader)}: ${context}: surfaceshader input has no nodename`);
    const node = topLevel.get(nodeName);
    if (!node) {
      throw new MaterialError(`${where(file, shader)}: ${context}: surfaceshader nodename '${nodeName}' references a node that does not exist`);
    }
    // A material of another shading model (standard_surface, ...) is not ours to load.
    if (node.tagName !== 'open_pbr_surface') continue;
    referenced.add(node);
    materials.push(readSurface(file, colorspace, node, materialName, inputs));
  }
  for (const node of root.children) {
    if (node.tagName === 'open_pbr_surface' && !referenced.has(node)) {
      materials.push(readSurface(file, colorspace, node, node.getAttribute('name') ?? '', inputs));
    }
  }
  if (materials.length === 0) throw new MaterialError(`${file}: no <open_pbr_surface> node found`);
  return materials;
}
