#!/usr/bin/env node
// Serves the OpenPBR material viewer on localhost: node viewer/serve.mjs [--port N] [--host H]
// The page and the repository files it reads (the parameter table, the kernel header, the
// bundled materials) are static; the WGSL and the tables are made here from the sources, so the
// viewer needs Node and `npm ci`, not the C++ build. WebGPU needs a secure context, which
// http://127.0.0.1 and http://localhost are.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { readFeatureToggles } from './features.mjs';
import { KernelCompiler } from './kernels.mjs';
import { readTableInc } from './tables.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

// What the page may read from the repository, by path prefix.
const STATIC_PREFIXES = [
  'viewer/index.html', 'viewer/style.css', 'viewer/src/', 'viewer/display.wgsl', 'materials/',
  'targets/source_text.mjs', 'targets/kernels/openpbr_render_kernel.h', 'slang/openpbr_parameters.h',
  'slang/openpbr_material_packing.h',
];
const CONTENT_TYPES = {
  '.html': 'text/html; charset=utf-8', '.css': 'text/css', '.mjs': 'text/javascript', '.js': 'text/javascript',
  '.wgsl': 'text/plain; charset=utf-8', '.h': 'text/plain; charset=utf-8', '.mtlx': 'application/xml',
  '.json': 'application/json', '.png': 'image/png',
};
// Each table's tracked files, concatenated in order as the build's openpbr_lut.bin is (the
// compensation tables, then the thin film's lobe table; slang/openpbr_lut.h).
const TABLES = {
  'lut.bin': ['slang/generated/openpbr_lut_values.inc', 'slang/generated/openpbr_film_lut_values.inc'],
  'fuzz_ltc.bin': ['slang/generated/openpbr_fuzz_ltc_values.inc'],
};

function parseArgs(argv) {
  const options = { port: 8732, host: '127.0.0.1' };
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--port' && i + 1 < argv.length) options.port = Number(argv[++i]);
    else if (argv[i] === '--host' && i + 1 < argv.length) options.host = argv[++i];
    else {
      console.error('usage: node viewer/serve.mjs [--port N (0: any free port)] [--host 127.0.0.1]');
      process.exit(2);
    }
  }
  if (!Number.isInteger(options.port) || options.port < 0 || options.port > 65535) {
    console.error('serve.mjs: --port needs an integer in [0, 65535]');
    process.exit(2);
  }
  return options;
}

function send(response, status, type, body, headers = {}) {
  response.writeHead(status, { 'content-type': type, 'cache-control': 'no-store', ...headers });
  response.end(body);
}

function sendError(response, status, message) {
  send(response, status, 'text/plain; charset=utf-8', message);
}

function serveStatic(response, relative) {
  const file = path.join(repoRoot, relative);
  const allowed = STATIC_PREFIXES.some((prefix) => relative === prefix || (prefix.endsWith('/') && relative.startsWith(prefix)));
  if (!allowed || relative.includes('..') || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
    sendError(response, 404, `not found: /${relative}`);
    return;
  }
  send(response, 200, CONTENT_TYPES[path.extname(file)] ?? 'application/octet-stream', fs.readFileSync(file));
}

async function serveKernel(response, promise) {
  try {
    const { code, seconds } = await promise;
    send(response, 200, CONTENT_TYPES['.wgsl'], code, { 'x-compile-seconds': seconds.toFixed(2) });
  } catch (error) {
    sendError(response, 500, error.message);
  }
}

function main() {
  const options = parseArgs(process.argv.slice(2));
  const toggles = readFeatureToggles(path.join(repoRoot, 'slang', 'openpbr_features.h'));
  const compiler = new KernelCompiler(repoRoot, toggles);
  const tables = new Map();

  const server = http.createServer((request, response) => {
    const url = new URL(request.url, 'http://localhost');
    const route = decodeURIComponent(url.pathname);
    if (request.method !== 'GET') {
      sendError(response, 405, 'GET only');
    } else if (route === '/') {
      serveStatic(response, 'viewer/index.html');
    } else if (route === '/api/materials') {
      const files = fs.readdirSync(path.join(repoRoot, 'materials')).filter((name) => name.endsWith('.mtlx')).sort();
      send(response, 200, CONTENT_TYPES['.json'], JSON.stringify(files));
    } else if (route === '/api/features') {
      send(response, 200, CONTENT_TYPES['.json'], JSON.stringify(toggles));
    } else if (route === '/api/kernel/render.wgsl') {
      const mask = Number(url.searchParams.get('features'));
      if (!Number.isInteger(mask) || mask < 0 || mask > toggles.reduce((all, toggle) => all | toggle.bit, 0)) {
        sendError(response, 400, 'features must be a feature mask (an integer of OPENPBR_FEATURE_BIT_* bits)');
        return;
      }
      serveKernel(response, compiler.renderKernel(mask));
    } else if (route === '/api/kernel/object_record.wgsl') {
      serveKernel(response, compiler.objectRecordKernel());
    } else if (route.startsWith('/api/tables/') && TABLES[route.slice('/api/tables/'.length)]) {
      const name = route.slice('/api/tables/'.length);
      try {
        if (!tables.has(name)) tables.set(name, Buffer.concat(TABLES[name].map((file) => readTableInc(path.join(repoRoot, file)))));
        send(response, 200, 'application/octet-stream', tables.get(name));
      } catch (error) {
        sendError(response, 500, error.message);
      }
    } else {
      serveStatic(response, route.slice(1));
    }
  });
  server.listen(options.port, options.host, () => {
    const { port } = server.address();
    const host = options.host.includes(':') ? `[${options.host}]` : options.host;
    console.log(`OpenPBR viewer: http://${host}:${port}/`);
  });
}

main();
