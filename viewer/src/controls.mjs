// One control per parameter of the table (parameters.mjs), grouped by the name's lobe prefix.
// Names, ranges and defaults come from the table; bounds beyond 10 (lengths, luminance, the
// specular weight, the Abbe number) get a number field instead of a slider.
const GROUPS = ['base', 'specular', 'transmission', 'subsurface', 'fuzz', 'coat', 'thin_film', 'emission', 'geometry'];
const SLIDER_LIMIT = 10;

function groupOf(name) {
  return GROUPS.find((group) => name.startsWith(`${group}_`)) ?? 'other';
}

function element(tag, attributes = {}, children = []) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  for (const child of children) node.append(child);
  return node;
}

function numberControl(id, value, low, high, onInput) {
  const slider = Number.isFinite(high) && high <= SLIDER_LIMIT;
  const input = element('input', {
    id, type: slider ? 'range' : 'number', min: String(low), max: String(high), step: slider ? String((high - low) / 1000) : 'any',
  });
  input.value = String(value);
  const readout = element('output', { for: id });
  readout.textContent = Number(value).toPrecision(3);
  input.addEventListener('input', () => {
    const number = Number(input.value);
    if (!Number.isFinite(number)) return;
    readout.textContent = number.toPrecision(3);
    onInput(number);
  });
  return {
    nodes: slider ? [input, readout] : [input],
    set(v) { input.value = String(v); readout.textContent = Number(v).toPrecision(3); },
  };
}

// Builds the panel into `container`; onChange(name, value) for every edit. Returns set(values),
// which shows a material's values without firing onChange.
export function buildControls(container, table, onChange) {
  const setters = new Map();
  const sections = new Map();
  for (const parameter of table.parameters) {
    const group = groupOf(parameter.name);
    if (!sections.has(group)) {
      const section = element('fieldset', { class: 'group' }, [element('legend')]);
      section.querySelector('legend').textContent = group.replace('_', ' ');
      sections.set(group, section);
      container.append(section);
    }
    const row = element('div', { class: 'control', 'data-parameter': parameter.name });
    const label = element('label', { for: `param-${parameter.name}` });
    label.textContent = parameter.name;
    row.append(label);
    const id = `param-${parameter.name}`;
    if (parameter.kind === 'FLOAT') {
      const control = numberControl(id, parameter.default, parameter.low, parameter.high, (v) => onChange(parameter.name, v));
      row.append(...control.nodes);
      setters.set(parameter.name, control.set);
    } else if (parameter.kind === 'COLOR' || parameter.kind === 'VECTOR2') {
      const isColor = parameter.kind === 'COLOR';
      const current = [...parameter.default];
      const swatch = isColor ? element('span', { class: 'swatch' }) : null;
      const paint = () => {
        if (swatch) swatch.style.background = `rgb(${current.map((c) => Math.round(255 * Math.min(Math.max(c, 0), 1) ** (1 / 2.2))).join(',')})`;
      };
      const parts = current.map((value, channel) => numberControl(`${id}-${channel}`, value,
        isColor ? parameter.low : -1, isColor ? parameter.high : 1, (v) => {
          current[channel] = v;
          paint();
          onChange(parameter.name, [...current]);
        }));
      const box = element('span', { class: 'components' });
      for (const part of parts) box.append(...part.nodes);
      if (swatch) row.append(swatch);
      row.append(box);
      paint();
      setters.set(parameter.name, (value) => {
        value.forEach((v, channel) => { current[channel] = v; parts[channel].set(v); });
        paint();
      });
    } else if (parameter.kind === 'BOOL') {
      const input = element('input', { id, type: 'checkbox' });
      input.checked = parameter.default;
      input.addEventListener('change', () => onChange(parameter.name, input.checked));
      row.append(input);
      setters.set(parameter.name, (value) => { input.checked = value; });
    } else {
      // A basis (geometry_normal/tangent): the render kernel sets the frame of each hit itself.
      const note = element('span', { class: 'note' });
      note.textContent = `${parameter.normalInput}, ${parameter.tangentInput}: the sphere's own frame (as openpbr render)`;
      row.append(note);
    }
    sections.get(group).append(row);
  }
  return (values) => {
    for (const [name, set] of setters) if (name in values) set(values[name]);
  };
}
