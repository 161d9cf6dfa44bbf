// The viewer's scene: one cell of `openpbr render` (host/preview/render.cpp, make_parameters and
// make_scene, with RenderSettings' defaults of host/preview/render.h): the unit sphere on the
// ground y = -1, the same camera, area light and sky, so that `openpbr render --materials
// FILE.mtlx --cell N` renders the very image the page renders. Buffer offsets come from the
// kernel header (layout.mjs); vectors are computed in float32 like the C++ host.
import { rec709ToWorkingSpace } from './colour_spaces.mjs';
import { required } from './layout.mjs';

const HEADER = 'openpbr_render_kernel.h';
const f = Math.fround;

// RenderSettings defaults (host/preview/render.h).
export const RENDER_DEFAULTS = { seed: 1, maxDepth: 8, maxVolumeEvents: 256, rouletteDepth: 3 };

const sub = (a, b) => [f(a[0] - b[0]), f(a[1] - b[1]), f(a[2] - b[2])];
const scale = (a, s) => [f(a[0] * s), f(a[1] * s), f(a[2] * s)];
const cross = (a, b) => [
  f(f(a[1] * b[2]) - f(a[2] * b[1])), f(f(a[2] * b[0]) - f(a[0] * b[2])), f(f(a[0] * b[1]) - f(a[1] * b[0])),
];
function normalized(a) {
  const length = f(Math.sqrt(f(f(f(a[0] * a[0]) + f(a[1] * a[1])) + f(a[2] * a[2]))));
  return scale(a, f(1 / length));
}

// The parameter buffer (uint) of a size x size image of one cell.
export function makeParameters(k, size, settings = RENDER_DEFAULTS) {
  const p = (name) => required(k, `OPENPBR_RENDER_PARAMETER_${name}`, HEADER);
  const flag = (name) => required(k, `OPENPBR_RENDER_FLAG_${name}`, HEADER);
  const parameters = new Uint32Array(p('COUNT'));
  parameters[p('WIDTH')] = size;
  parameters[p('HEIGHT')] = size;
  parameters[p('SEED')] = settings.seed;
  parameters[p('CELL_SIZE')] = size;
  parameters[p('COLUMNS')] = 1;
  parameters[p('CELL_COUNT')] = 1;
  parameters[p('GROUND_MATERIAL')] = 1; // the sphere's material is 0, the ground's follows
  parameters[p('FLAGS')] = flag('GROUND') | flag('SKY') | flag('LIGHT');
  parameters[p('MAX_DEPTH')] = settings.maxDepth;
  parameters[p('MAX_VOLUME_EVENTS')] = settings.maxVolumeEvents;
  parameters[p('RR_DEPTH')] = settings.rouletteDepth;
  return parameters;
}

// The scene buffer (float): the header, then the cell's object records; `record` holds what the
// material analysis (object_record.slang) wrote for the sphere's material, and `wavelengths`
// the library's default wavelengths.
export function makeScene(k, record, wavelengths) {
  const s = (name) => required(k, `OPENPBR_RENDER_SCENE_${name}`, HEADER);
  const o = (name) => required(k, `OPENPBR_RENDER_OBJECT_${name}`, HEADER);
  const objectFloats = required(k, 'OPENPBR_RENDER_OBJECT_FLOATS', HEADER);
  const scene = new Float32Array(s('COUNT') + required(k, 'OPENPBR_RENDER_MAX_OBJECTS', HEADER) * objectFloats);
  const put = (index, value) => scene.set(value, index);
  const camera = [0, 0.7, 4.5].map(f);
  const target = [0, -0.1, 0].map(f);
  const tanHalfFov = f(0.34);
  const forward = normalized(sub(target, camera));
  const right = normalized(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  put(s('CAMERA_POSITION'), camera);
  put(s('CAMERA_FORWARD'), forward);
  put(s('CAMERA_RIGHT'), scale(right, tanHalfFov));
  put(s('CAMERA_UP'), scale(up, tanHalfFov));
  scene[s('SPHERE_RADIUS')] = 1;
  const light = [-3.5, 5.5, 3.5];
  put(s('LIGHT_CENTER'), light);
  scene[s('LIGHT_RADIUS')] = 1;
  // The light and sky colours are linear Rec.709, stored in the working space (as render.cpp).
  put(s('LIGHT_RADIANCE'), rec709ToWorkingSpace([40, 38, 34].map(f)));
  put(s('SKY_ZENITH'), rec709ToWorkingSpace([0.16, 0.26, 0.5].map(f)));
  put(s('SKY_HORIZON'), rec709ToWorkingSpace([0.7, 0.75, 0.85].map(f)));
  put(s('ENVIRONMENT'), [0.2, 0.2, 0.2]);
  put(s('SUN_DIRECTION'), normalized(light.map(f)));
  put(s('SUN_GLOW'), rec709ToWorkingSpace([0.6, 0.45, 0.25].map(f)));
  scene[s('SUN_EXPONENT')] = 12;
  scene[s('NITS_TO_UNITS')] = 0.01; // kNitsToRenderUnits
  scene[s('CHECKER_SIZE')] = 0.5;
  scene[s('CHECKER_DARK')] = 0.55;
  put(s('DEFAULT_WAVELENGTHS'), wavelengths);
  // The sphere: record fields from the analysis, then its place and material.
  const base = s('COUNT');
  put(base, record);
  put(base + o('CENTER'), [0, 0, 0]);
  scene[base + o('RADIUS')] = 1;
  scene[base + o('MATERIAL')] = 0;
  return scene;
}

// The ground (render_ground_material in host/preview/render.cpp): default inputs with a grey
// base and a rough specular; the kernel multiplies its base color by the checker.
export function groundValues(values) {
  return { ...values, base_color: [0.5, 0.5, 0.5], specular_roughness: 0.6 };
}
