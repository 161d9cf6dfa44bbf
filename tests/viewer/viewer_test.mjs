#!/usr/bin/env node
// The material viewer in a real browser: serves viewer/ (node viewer/serve.mjs), drives Debian's
// headless Chromium on SwiftShader through puppeteer-core, renders three materials (a plain
// dielectric, a coated metal, a rough glass) to SPP samples at SIZE x SIZE, reads the
// accumulation back and compares it with `openpbr render` on the CPU (same scene, camera, seed
// and spp: --materials FILE --cell SIZE). Then a material whose base colour is 5 % off must
// fail the same comparison, and a broken .mtlx must show a visible error while the page keeps
// working. While the coated metal's kernel compiles (its request held until then), the caption
// must say so with a running count of seconds, in a screenshot (WORK/viewer_compiling.png); a
// busy server (503, answered here) must be shown and asked again; a compile that fails (the
// server's 500, answered here) must show its message in the red box
// (WORK/viewer_compile_failed.png). Exit status 0 when every check passes; 1 with the failed
// checks listed.
// Usage: node tests/viewer/viewer_test.mjs --openpbr BUILD/openpbr --work DIR
//   [--chromium /usr/bin/chromium] [--screenshot FILE.png]
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { launchChromium, startServer, waitForSamples } from '../../viewer/headless.mjs';
import { parseParameterTable } from '../../viewer/src/parameters.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const DATA = path.join(repoRoot, 'tests', 'viewer', 'data');
const SIZE = 64;
const SPP = 16;
// The comparison, per colour channel: the image mean of the browser's render against the
// CPU's. Its noise is the standard error of a 64x64 image mean at 16 spp, from the CPU render's
// own per-pixel variance of the mean (sqrt(sum of the variances) / pixels), for the difference
// of two renders (x sqrt 2). Measured (2026-11-27, SwiftShader in Chromium 156): 0.15-0.16 % of
// the mean for the plain dielectric, 0.54-0.69 % for the coated metal, 0.43-0.63 % for the rough
// glass. A mean outside 4 of those standard errors fails. Both renders use seed 1, so the right
// material differs by float rounding only (measured: at most 0.053 standard errors; pixel RMSE
// 0.01-0.04 x the noise), while the base colour 5 % off moves the plain dielectric's means by
// 14.7, 8.9 and 5.0 standard errors (R, G, B).
const SIGMAS = 4;
const MATERIALS = [
  { file: 'plain_dielectric.mtlx', features: 'base' },
  { file: 'coated_metal.mtlx', features: 'coat+metal', showCompile: true },
  { file: 'rough_glass.mtlx', features: 'transmission' },
];
function parseArgs(argv) {
  const options = { chromium: '/usr/bin/chromium', screenshot: null };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (!['openpbr', 'work', 'chromium', 'screenshot'].includes(key) || i + 1 >= argv.length) {
      throw new Error(`usage: viewer_test.mjs --openpbr BIN --work DIR [--chromium BIN] [--screenshot PNG] (at '${argv[i]}')`);
    }
    options[key] = argv[i + 1];
  }
  if (!options.openpbr || !options.work) throw new Error('--openpbr and --work are required');
  return options;
}

const failures = [];
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}

function cpuReference(options, file) {
  const stem = path.join(options.work, path.basename(file, '.mtlx'));
  const result = spawnSync(options.openpbr, [
    'render', '--materials', file, '--cell', String(SIZE), '--spp', String(SPP), '--seed', '1', '--no-labels', '--quiet',
    '-o', `${stem}_cpu.png`, '--linear', `${stem}_cpu.json`,
  ], { encoding: 'utf8' });
  if (result.status !== 0) throw new Error(`openpbr render ${file} failed:\n${result.stdout}${result.stderr}`);
  return JSON.parse(fs.readFileSync(`${stem}_cpu.json`, 'utf8'));
}

// Per channel: the difference of the image means in standard errors of that difference; and per
// pixel: the RMS difference against the RMS noise of the difference of two renders (the check
// of `openpbr render --compare`), which catches a wrong picture with a right mean.
function compare(browser, cpu) {
  const pixels = cpu.width * cpu.height;
  const channels = [];
  let squares = 0;
  let noise = 0;
  for (let channel = 0; channel < 3; channel++) {
    let sumBrowser = 0;
    let sumCpu = 0;
    let variance = 0;
    for (let pixel = 0; pixel < pixels; pixel++) {
      const index = pixel * 3 + channel;
      sumBrowser += browser.mean[index];
      sumCpu += cpu.mean[index];
      variance += cpu.variance_of_mean[index];
      squares += (browser.mean[index] - cpu.mean[index]) ** 2;
    }
    noise += 2 * variance;
    const standardError = Math.sqrt(2 * variance) / pixels;
    const difference = (sumBrowser - sumCpu) / pixels;
    channels.push({ mean: sumCpu / pixels, difference, standardError, sigmas: Math.abs(difference) / standardError });
  }
  return { channels, rmse: Math.sqrt(squares / (3 * pixels)), noise: Math.sqrt(noise / (3 * pixels)) };
}

function describe(result) {
  return result.channels.map((c, i) => `${'RGB'[i]} mean ${c.mean.toFixed(4)} diff ${c.difference.toExponential(2)} `
    + `(SE ${c.standardError.toExponential(2)} = ${(100 * c.standardError / c.mean).toFixed(2)} %, ${c.sigmas.toFixed(3)} SE)`).join('; ')
    + `; pixel RMSE ${result.rmse.toExponential(2)} vs noise ${result.noise.toExponential(2)}`;
}

const within = (result) => result.channels.every((c) => c.sigmas <= SIGMAS) && result.rmse < result.noise;

// Intercepts the page's render-kernel requests until end(): next() resolves to the next one
// (held: the caller continues it to the server or answers it), other requests go on.
async function interceptKernelRequests(page) {
  await page.setRequestInterception(true);
  const held = [];
  let wake = () => {};
  const onRequest = (intercepted) => {
    if (intercepted.isInterceptResolutionHandled()) return;
    if (!intercepted.url().includes('/api/kernel/render.wgsl')) {
      intercepted.continue();
      return;
    }
    held.push(intercepted);
    wake();
  };
  page.on('request', onRequest);
  return {
    // The page asks within a second or two (the analysis runs first); a kernel it already has
    // would never be asked for: an error, not a hang.
    next: () => new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error('the page asked for no render kernel within 120 s')), 120000);
      wake = () => {
        if (held.length === 0) return;
        clearTimeout(timer);
        wake = () => {};
        resolve(held.shift());
      };
      wake();
    }),
    end: async () => {
      page.off('request', onRequest);
      await page.setRequestInterception(false);
    },
  };
}

// Answers a held request here with a status, headers and a text body.
const answer = (request, status, body, headers = {}) => request.respond({ status, headers, contentType: 'text/plain; charset=utf-8', body });

// The captions the page shows, in order, from here on (window.captionLog).
async function recordCaptions(page) {
  await page.evaluate(() => {
    const status = document.getElementById('status');
    window.captionLog = [status.textContent];
    window.captionObserver ??= new MutationObserver(() => window.captionLog.push(status.textContent));
    window.captionObserver.observe(status, { childList: true, characterData: true, subtree: true });
  });
}

// With the kernel request of `features` held: the caption counts the compile's seconds (waits
// for 1 s or more), and the screenshot shows it; then the request goes on, and the captions
// must have named the compile, the pipeline build and the result, in that order.
async function showCompile(page, features, screenshot) {
  const pattern = `compiling kernel \\{${features.replace('+', '\\+')}\\}… `;
  await page.waitForFunction((p) => new RegExp(`${p}[1-9]\\d* s$`).test(document.getElementById('status').textContent),
    { timeout: 60000, polling: 100 }, pattern);
  const caption = await page.$eval('#status', (status) => status.textContent);
  await page.screenshot({ path: screenshot });
  check(new RegExp(`^\\S+: ${pattern}[1-9]\\d* s$`).test(caption), `while the kernel compiles, the caption says so and counts ('${caption}', ${screenshot})`);
}

function checkCaptions(captions, features) {
  const label = `{${features}}`;
  const compiling = captions.findIndex((c) => c.includes(`compiling kernel ${label}… 0 s`));
  const building = captions.findIndex((c) => c.includes(`building the pipelines of kernel ${label}… 0 s`));
  const result = captions.findIndex((c) => / kernel \{[^}]*\} \(WGSL \d+\.\d s, pipelines \d+\.\d s\)$/.test(c) && c.includes(label));
  check(compiling >= 0 && compiling < building && building < result,
    `the captions name the compile, the pipeline build and the result in turn (${[compiling, building, result].map((i) => `'${captions[i]}'`).join(', ')})`);
}

// Loads a .mtlx text through the page (the drop path), waits for SPP samples, reads the mean.
// `screenshot`: the kernel's compile is held, shown and checked first (showCompile).
async function renderInPage(page, text, name, features = null, screenshot = null) {
  const kernels = screenshot ? await interceptKernelRequests(page) : null;
  if (kernels) await recordCaptions(page);
  const generation = await page.evaluate((t, n) => window.openpbrViewer.loadMaterialText(t, n), text, name);
  if (generation === false) throw new Error(`the page refused ${name}: ${(await page.evaluate(() => window.openpbrViewer.state())).error}`);
  if (kernels) {
    const request = await kernels.next();
    await showCompile(page, features, screenshot).finally(async () => {
      await request.continue();
      await kernels.end();
    });
  }
  const state = await waitForSamples(page, SPP, generation);
  if (state.error) throw new Error(`page error while rendering ${name}: ${state.error}`);
  if (kernels) checkCaptions(await page.evaluate(() => window.captionLog), features);
  return { state, image: await page.evaluate(() => window.openpbrViewer.readMean()) };
}

// A compile that fails: the plain dielectric with fuzz (a feature set not built yet), its kernel
// request answered 500 with a compiler's message, as the server answers a failed compile.
async function checkFailedCompile(page, screenshot) {
  const text = fs.readFileSync(path.join(DATA, 'plain_dielectric.mtlx'), 'utf8')
    .replace('<input name="specular_roughness"', '<input name="fuzz_weight" type="float" value="0.5" />\n    <input name="specular_roughness"');
  const message = 'compiling the render kernel {fuzz} failed (slangc.mjs targets/kernels/render_steps.slang):\nrender_steps.slang(1): error 30015: a message from the browser test';
  const kernels = await interceptKernelRequests(page);
  await recordCaptions(page);
  const generation = await page.evaluate((t) => window.openpbrViewer.loadMaterialText(t, 'fuzz_compile_fails.mtlx'), text);
  // First the server is busy (503, Retry-After 1 s): the page must say so and ask again.
  await answer(await kernels.next(), 503, 'the compile queue is full; retry in 1 s\n', { 'retry-after': '1' });
  const retried = await kernels.next();
  const busy = (await page.evaluate(() => window.captionLog)).find((c) => c.includes("the server's compile queue is full"));
  check(/: the server's compile queue is full; asking again for kernel \{fuzz\} in 1 s… \d+ s$/.test(busy ?? ''),
    `a busy server (503) is shown in the caption ('${busy}') and asked again`);
  await answer(retried, 500, `500 Internal Server Error: ${message}\n`);
  await kernels.end();
  const state = await waitForSamples(page, 1, generation);
  const box = await page.$eval('#error', (element) => !element.hidden && element.textContent);
  check(typeof box === 'string' && box.includes(message) && state.error.includes(message),
    `a failed compile shows the compiler's message in the red box ('${String(box).replace(/\n/g, ' | ')}')`);
  check(state.features === 'fuzz' && state.status === `${state.name}: kernel {fuzz} failed; the message is above the image`,
    `the caption names the kernel that failed ('${state.status}', ${screenshot})`);
  await page.screenshot({ path: screenshot });
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  fs.mkdirSync(options.work, { recursive: true });
  const { server, url } = await startServer();
  let browser;
  try {
    browser = await launchChromium(options.chromium, options.work);
    const page = await browser.newPage();
    page.on('pageerror', (error) => check(false, `no uncaught page error (${error.message})`));
    // The page starts on the bundled default material (base features, like the plain dielectric).
    await page.goto(`${url}?size=${SIZE}&spp=${SPP}&seed=1`);
    const initial = await waitForSamples(page, SPP);
    check(initial.error === '', `the page starts without an error${initial.error ? ` (${initial.error})` : ''}`);
    check(initial.adapter !== '', 'WebGPU adapter present');

    for (const material of MATERIALS) {
      const file = path.join(DATA, material.file);
      const cpu = cpuReference(options, file);
      const screenshot = material.showCompile ? path.join(options.work, 'viewer_compiling.png') : null;
      const { state, image } = await renderInPage(page, fs.readFileSync(file, 'utf8'), material.file, material.features, screenshot);
      check(state.features === material.features, `${material.file}: kernel specialized to {${state.features}} (expected {${material.features}})`);
      check(image.samples === SPP && image.size === cpu.width, `${material.file}: ${image.samples} spp at ${image.size}px`);
      const result = compare(image, cpu);
      check(within(result), `${material.file} matches openpbr render within ${SIGMAS} SE: ${describe(result)}`);
      if (material === MATERIALS[0]) {
        // The same material with its base colour 5 % higher must not pass against the original.
        const wrongText = fs.readFileSync(file, 'utf8').replace('value="0.8, 0.35, 0.2"', 'value="0.84, 0.3675, 0.21"');
        check(wrongText.includes('0.3675'), 'the wrong material differs from the right one');
        const wrong = await renderInPage(page, wrongText, 'plain_dielectric_5_percent_off.mtlx');
        const wrongResult = compare(wrong.image, cpu);
        check(!within(wrongResult), `base colour 5 % off fails the comparison: ${describe(wrongResult)}`);
      }
    }

    // The page's MaterialX reader takes every bundled material, as the C++ loader does (the
    // gallery of openpbr render loads them all), under the same names.
    const materialsDir = path.join(repoRoot, 'materials');
    const bundled = fs.readdirSync(materialsDir).filter((name) => name.endsWith('.mtlx'));
    const refused = [];
    for (const name of bundled) {
      const parsed = await page.evaluate((t, n) => window.openpbrViewer.parse(t, n), fs.readFileSync(path.join(materialsDir, name), 'utf8'), name);
      if (!Array.isArray(parsed) || parsed.length === 0) refused.push(`${name}: ${parsed}`);
    }
    check(bundled.length > 50 && refused.length === 0, `the page reads all ${bundled.length} bundled materials${refused.length ? `; refused: ${refused.join('; ')}` : ''}`);
    const unknownInput = await page.evaluate(() => window.openpbrViewer.parse(
      '<materialx colorspace="lin_rec709"><open_pbr_surface name="s"><input name="base_colour" type="color3" value="1, 1, 1"/></open_pbr_surface></materialx>', 'typo.mtlx'));
    check(typeof unknownInput === 'string' && unknownInput.includes("input 'base_colour': unknown input name"),
      `an unknown input is refused with the C++ loader's message (${unknownInput})`);

    // Every parameter of the table has a control, and editing one restarts the accumulation.
    const table = parseParameterTable(fs.readFileSync(path.join(repoRoot, 'slang', 'openpbr_parameters.h'), 'utf8'));
    const controls = await page.$$eval('[data-parameter]', (rows) => rows.map((row) => row.dataset.parameter));
    const missing = table.parameters.map((p) => p.name).filter((name) => !controls.includes(name));
    check(missing.length === 0 && table.parameters.length > 40,
      `a control for each of the ${table.parameters.length} parameters${missing.length ? ` (missing: ${missing.join(', ')})` : ''}`);
    const before = await page.evaluate(() => window.openpbrViewer.state());
    await page.$eval('#param-specular_roughness', (input) => {
      input.value = '0.5';
      input.dispatchEvent(new Event('input'));
    });
    const after = await waitForSamples(page, 2, before.generation + 1);
    // A new generation starts its sample count from 0 (main.mjs restart).
    check(after.generation === before.generation + 1 && after.error === '' && after.samples >= 2,
      `editing specular_roughness restarts the accumulation (generation ${before.generation} -> ${after.generation}, now ${after.samples} spp)`);

    await checkFailedCompile(page, path.join(options.work, 'viewer_compile_failed.png'));

    const broken = await page.evaluate(() => window.openpbrViewer.loadMaterialText('<materialx><open_pbr_surface name="x"', 'broken.mtlx'));
    const errorShown = await page.$eval('#error', (box) => !box.hidden && box.textContent);
    check(broken === false && /broken\.mtlx: malformed XML/.test(errorShown || ''), `a broken .mtlx shows a visible error ('${errorShown}')`);
    const alive = await page.evaluate(() => window.openpbrViewer.state().samples);
    check(Number.isInteger(alive), 'the page still answers after the broken file');
    if (options.screenshot) await page.screenshot({ path: options.screenshot });
  } finally {
    await browser?.close();
    server.kill();
  }
  if (failures.length > 0) {
    console.log(`\n${failures.length} check(s) failed:\n  ${failures.join('\n  ')}`);
    process.exit(1);
  }
  console.log('\nall checks passed');
}

main().catch((error) => {
  console.error(`viewer_test: ${error.message}`);
  process.exit(1);
});
