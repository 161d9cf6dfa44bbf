#!/usr/bin/env node
// Times the viewer in headless Chromium on SwiftShader (docs/performance.md, "Browser viewer"):
// the time to first image of a fresh server and page (Slang compiles, SwiftShader pipeline
// builds, the first sample), samples per second after it, and the render kernel's WGSL compile
// and pipeline build for the feature sets asked for. Prints JSON; optionally a screenshot.
// Usage: node viewer/bench.mjs [--size 512] [--samples 8] [--material open_pbr_default]
//   [--kernels 1023,...] [--screenshot FILE.png] [--chromium /usr/bin/chromium]
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { launchChromium, startServer, waitForSamples } from './headless.mjs';

const options = { size: 512, samples: 8, material: 'open_pbr_default', kernels: '', screenshot: null, chromium: '/usr/bin/chromium' };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) {
  const key = argv[i].replace(/^--/, '');
  if (!(key in options) || i + 1 >= argv.length) {
    console.error('usage: node viewer/bench.mjs [--size N] [--samples N] [--material STEM] [--kernels MASK,...] [--screenshot PNG] [--chromium BIN]');
    process.exit(2);
  }
  options[key] = argv[i + 1];
}

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'openpbr-viewer-bench-'));
const { server, url } = await startServer();
let browser;
try {
  browser = await launchChromium(options.chromium, work, { width: 1180, height: 600 });
  const page = await browser.newPage();
  await page.goto(`${url}?size=${options.size}&spp=${options.samples}&material=${options.material}`);
  const state = await waitForSamples(page, Number(options.samples));
  if (state.error) throw new Error(state.error);
  const report = {
    adapter: state.adapter,
    size: Number(options.size),
    material: state.name,
    features: state.features,
    time_to_first_image_s: state.firstImageSeconds,
    samples: state.samples,
    samples_per_second: await page.evaluate(() => window.openpbrViewer.samplesPerSecond()),
    kernel: state.kernel,
    kernels: {},
  };
  if (options.screenshot) await page.screenshot({ path: options.screenshot });
  for (const mask of options.kernels.split(',').filter(Boolean).map(Number)) {
    report.kernels[mask] = await page.evaluate((m) => window.openpbrViewer.buildKernel(m), mask);
  }
  console.log(JSON.stringify(report, null, 2));
} finally {
  await browser?.close();
  server.kill();
  fs.rmSync(work, { recursive: true, force: true });
}
