// The viewer in headless Chromium, for the browser test (tests/viewer/viewer_test.mjs) and the
// timing script (viewer/bench.mjs): the server on a free port, and Debian's Chromium with the
// flags that give it a WebGPU adapter on SwiftShader (its Vulkan driver) and canvases that
// screenshots capture (--use-angle=swiftshader). WebGPU needs a secure context: 127.0.0.1 is one.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import puppeteer from 'puppeteer-core';

const viewerDir = path.dirname(fileURLToPath(import.meta.url));

export const CHROMIUM_FLAGS = [
  '--headless=new', '--no-sandbox', '--enable-unsafe-webgpu', '--enable-unsafe-swiftshader', '--enable-features=Vulkan',
  '--use-vulkan=swiftshader', '--use-angle=swiftshader', '--disable-background-networking', '--disable-component-update',
  '--disable-sync', '--no-first-run',
];

// Starts viewer/serve.mjs on a free port; resolves to { server, url } once it prints its URL.
export async function startServer() {
  const server = spawn(process.execPath, [path.join(viewerDir, 'serve.mjs'), '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = await new Promise((resolve, reject) => {
    server.on('exit', (code) => reject(new Error(`viewer/serve.mjs exited (${code})`)));
    server.stdout.on('data', (data) => {
      const match = /http:\/\/127\.0\.0\.1:\d+\//.exec(String(data));
      if (match) resolve(match[0]);
    });
  });
  return { server, url };
}

// Chromium with a fresh profile under workDir; a missing executable is an error, not a skip.
export async function launchChromium(executable, workDir, viewport = { width: 1280, height: 760 }) {
  if (!fs.existsSync(executable)) {
    throw new Error(`no Chromium at ${executable}: install Debian's chromium (scripts/setup.sh does) or pass --chromium`);
  }
  return puppeteer.launch({
    executablePath: executable,
    args: [...CHROMIUM_FLAGS, `--user-data-dir=${fs.mkdtempSync(path.join(workDir, 'chromium-'))}`],
    protocolTimeout: 0,
    defaultViewport: viewport,
  });
}

// Waits until the page has rendered `samples` samples of `generation` (any, when null) or shows
// an error; returns its state.
export async function waitForSamples(page, samples, generation = null) {
  await page.waitForFunction((spp, g) => {
    const s = window.openpbrViewer?.state();
    return s && (s.error !== '' || ((g === null || s.generation === g) && s.samples >= spp));
  }, { timeout: 0, polling: 250 }, samples, generation);
  return page.evaluate(() => window.openpbrViewer.state());
}
