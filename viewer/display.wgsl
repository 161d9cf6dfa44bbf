// Shows the accumulation buffer (targets/kernels/openpbr_render_kernel.h: per pixel the sum of
// the radiance, then five more floats) as `openpbr render` writes its PNG
// (host/preview/render_image.cpp): mean radiance x exposure, the ACES filmic fit of Narkowicz
// (2015), then the sRGB transfer function (the canvas is a plain 8-bit format).
struct Display {
  width : u32,
  height : u32,
  samples : u32,
  record_floats : u32,
  exposure : f32,
}

@group(0) @binding(0) var<storage, read> accumulation : array<f32>;
@group(0) @binding(1) var<uniform> display : Display;

// One triangle that covers the viewport.
@vertex
fn vertex_main(@builtin(vertex_index) index : u32) -> @builtin(position) vec4f {
  let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
  return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}

fn aces_fit(x : vec3f) -> vec3f {
  let v = max(x, vec3f(0.0));
  return clamp((v * (2.51 * v + 0.03)) / (v * (2.43 * v + 0.59) + 0.14), vec3f(0.0), vec3f(1.0));
}

fn srgb_encode(linear : vec3f) -> vec3f {
  let x = clamp(linear, vec3f(0.0), vec3f(1.0));
  return select(1.055 * pow(x, vec3f(1.0 / 2.4)) - 0.055, 12.92 * x, x <= vec3f(0.0031308));
}

@fragment
fn fragment_main(@builtin(position) position : vec4f) -> @location(0) vec4f {
  let pixel = vec2u(position.xy);
  if (display.samples == 0u || pixel.x >= display.width || pixel.y >= display.height) {
    return vec4f(0.0, 0.0, 0.0, 1.0);
  }
  let base = (pixel.y * display.width + pixel.x) * display.record_floats;
  let sum = vec3f(accumulation[base], accumulation[base + 1u], accumulation[base + 2u]);
  let mean = sum / f32(display.samples);
  return vec4f(srgb_encode(aces_fit(mean * display.exposure)), 1.0);
}
