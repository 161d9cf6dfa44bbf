// The viewer's HTTP server (viewer/serve.mjs starts it; docs/viewer.md): the page, the repository
// files it reads, the tables, and the WGSL kernels compiled on request (viewer/kernels.mjs).
// Every request gets an answer, and nothing outside the page's set of files is served:
// - 405 for a method other than GET and HEAD (CONNECT included);
// - 400 for a request target that is not a path, a malformed percent-escape or UTF-8, a control
//   character (NUL included), an encoded slash or backslash, a GET with a body, or what Node's
//   parser refuses (raw garbage, a bad header); 431 for headers or a request line over 16 KB,
//   414 for a target over LIMITS.targetLength;
// - 403 for a Host header other than the loopback names when the server listens on loopback (a
//   page elsewhere cannot reach it through DNS rebinding);
// - 404 for any path outside the set: '..' and '.' segments (encoded or not), empty segments
//   (doubled slashes), names starting with a dot, files whose real path (symbolic links
//   resolved) leaves the set, anything not a regular file;
// - 503 with Retry-After when the compile queue is full, 500 when a compile fails (the compiler's
//   message) or a handler throws (logged; the server goes on).
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';

import { fullMask } from './features.mjs';
import { QueueFullError } from './kernels.mjs';
import { readTableInc } from './tables.mjs';

// What the page may read from the repository: exact files, and folders (ending in '/') whose
// files it may read at any depth.
export const STATIC_FILES = [
  'viewer/index.html', 'viewer/style.css', 'viewer/src/', 'viewer/display.wgsl', 'materials/',
  'targets/source_text.mjs', 'targets/kernels/openpbr_render_kernel.h', 'slang/openpbr_parameters.h',
  'slang/openpbr_material_packing.h',
];
const CONTENT_TYPES = {
  '.html': 'text/html; charset=utf-8', '.css': 'text/css; charset=utf-8', '.mjs': 'text/javascript; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8', '.wgsl': 'text/plain; charset=utf-8', '.h': 'text/plain; charset=utf-8',
  '.mtlx': 'application/xml', '.json': 'application/json', '.png': 'image/png', '.txt': 'text/plain; charset=utf-8',
};
const TEXT = CONTENT_TYPES['.txt'];
// Each table's tracked files, concatenated in order as the build's openpbr_lut.bin is (the
// compensation tables, then the thin film's lobe table; slang/openpbr_lut.h).
const TABLES = {
  'lut.bin': ['slang/generated/openpbr_lut_values.inc', 'slang/generated/openpbr_film_lut_values.inc'],
  'fuzz_ltc.bin': ['slang/generated/openpbr_fuzz_ltc_values.inc'],
};
export const LIMITS = {
  targetLength: 2048, // characters of a request target (path and query), e.g. 4096
  headersSeconds: 15, // to receive a request's headers, e.g. 60
  requestSeconds: 30, // to receive a whole request, e.g. 120
  checkSeconds: 5, // how often connections are checked against the two, e.g. 30 (Node's default)
  connections: 256, // open connections; more are dropped, e.g. 1024
};
// Characters a path may hold before decoding (RFC 3986 pchar and '/').
const RAW_PATH = /^\/[A-Za-z0-9\-._~!$&'()*+,;=:@%/]*$/;
// A path segment the server serves: no leading dot (so no '.', '..' or hidden files), no empty one.
const SEGMENT = /^[A-Za-z0-9_][A-Za-z0-9_.+-]*$/;

function isAllowed(relative) {
  return STATIC_FILES.some((entry) => relative === entry || (entry.endsWith('/') && relative.startsWith(entry)));
}

// The request target (origin form, "/path?query") as { route, query } with the path decoded,
// or { status, message } for a target that is not one.
export function parseTarget(target) {
  if (target.length > LIMITS.targetLength) return { status: 414, message: `request target over ${LIMITS.targetLength} characters` };
  const queryStart = target.indexOf('?');
  const rawPath = queryStart < 0 ? target : target.slice(0, queryStart);
  if (!RAW_PATH.test(rawPath)) return { status: 400, message: 'the request target must be a path of URL characters, e.g. /viewer/index.html' };
  const segments = [];
  for (const raw of rawPath.slice(1).split('/')) {
    let segment;
    try {
      segment = decodeURIComponent(raw);
    } catch {
      return { status: 400, message: 'malformed percent-escape in the path' };
    }
    if (/[\x00-\x1f\x7f/\\]/.test(segment)) return { status: 400, message: 'a control character, slash or backslash encoded in the path' };
    segments.push(segment);
  }
  return { route: `/${segments.join('/')}`, query: new URLSearchParams(queryStart < 0 ? '' : target.slice(queryStart + 1)) };
}

// The real path of the repository file a route names when it is in STATIC_FILES, with every
// symbolic link resolved and the result in the set too; null otherwise.
export async function resolveStatic(root, route) {
  const segments = route.slice(1).split('/');
  if (!segments.every((segment) => SEGMENT.test(segment)) || !isAllowed(segments.join('/'))) return null;
  try {
    const realRoot = await fs.promises.realpath(root);
    const real = await fs.promises.realpath(path.join(root, ...segments));
    const relative = path.relative(realRoot, real);
    if (relative.startsWith('..') || path.isAbsolute(relative) || !isAllowed(relative.split(path.sep).join('/'))) return null;
    return (await fs.promises.stat(real)).isFile() ? real : null;
  } catch {
    return null; // missing, unreadable or a loop of links: not in the set
  }
}

function send(response, status, type, body, headers = {}) {
  if (response.headersSent || response.destroyed) return;
  response.writeHead(status, {
    'content-type': type, 'content-length': Buffer.byteLength(body), 'cache-control': 'no-store',
    'x-content-type-options': 'nosniff', ...headers,
  });
  response.end(body);
}

function sendError(response, status, message, headers = {}) {
  send(response, status, TEXT, `${status} ${http.STATUS_CODES[status]}: ${message}\n`, headers);
}

// A printable, bounded form of a client's text for the log.
function quoted(text) {
  return JSON.stringify(text.length > 200 ? `${text.slice(0, 200)}...` : text);
}

function hostAllowed(host, loopbackOnly) {
  if (!loopbackOnly || host === undefined) return true;
  const name = host.startsWith('[') ? host.slice(0, host.indexOf(']') + 1) : host.split(':')[0];
  return ['localhost', '[::1]'].includes(name.toLowerCase()) || /^127\.\d+\.\d+\.\d+$/.test(name);
}

async function serveKernel(response, start) {
  let compiled;
  try {
    compiled = start();
  } catch (error) {
    if (!(error instanceof QueueFullError)) throw error;
    sendError(response, 503, `${error.message}; retry in ${error.retryAfterSeconds} s`, { 'retry-after': String(error.retryAfterSeconds) });
    return;
  }
  let result;
  try {
    result = await compiled;
  } catch (error) {
    sendError(response, 500, error.message);
    return;
  }
  send(response, 200, CONTENT_TYPES['.wgsl'], result.code, { 'x-compile-seconds': result.seconds.toFixed(2) });
}

// The routes besides the static files: route -> async (response, query) => answer.
function apiRoutes({ root, toggles, compiler }) {
  const tables = new Map();
  const routes = {
    '/api/materials': async (response) => {
      const names = await fs.promises.readdir(path.join(root, 'materials'));
      send(response, 200, CONTENT_TYPES['.json'], JSON.stringify(names.filter((name) => name.endsWith('.mtlx') && SEGMENT.test(name)).sort()));
    },
    '/api/features': async (response) => send(response, 200, CONTENT_TYPES['.json'], JSON.stringify(toggles)),
    '/api/compiles': async (response) => send(response, 200, CONTENT_TYPES['.json'], JSON.stringify(compiler.status())),
    '/api/kernel/render.wgsl': async (response, query) => {
      const text = query.get('features') ?? '';
      const mask = /^\d{1,10}$/.test(text) ? Number(text) : -1;
      if (mask < 0 || mask > fullMask(toggles) || (mask & ~fullMask(toggles)) !== 0) {
        sendError(response, 400, `features must be a feature mask, an integer of OPENPBR_FEATURE_BIT_* bits in [0, ${fullMask(toggles)}] (got ${quoted(text)})`);
        return;
      }
      await serveKernel(response, () => compiler.renderKernel(mask));
    },
    '/api/kernel/object_record.wgsl': (response) => serveKernel(response, () => compiler.objectRecordKernel()),
  };
  for (const [name, files] of Object.entries(TABLES)) {
    routes[`/api/tables/${name}`] = async (response) => {
      if (!tables.has(name)) tables.set(name, Buffer.concat(files.map((file) => readTableInc(path.join(root, file)))));
      send(response, 200, 'application/octet-stream', tables.get(name));
    };
  }
  return routes;
}

async function handle(request, response, context) {
  if (request.method !== 'GET' && request.method !== 'HEAD') {
    sendError(response, 405, `${request.method} is not served; GET and HEAD are`, { allow: 'GET, HEAD', connection: 'close' });
    return;
  }
  const target = parseTarget(request.url);
  if (target.status) {
    sendError(response, target.status, target.message);
    return;
  }
  if (!hostAllowed(request.headers.host, context.loopbackOnly)) {
    sendError(response, 403, 'this server answers requests for 127.0.0.1, localhost and [::1] only (its Host header)');
    return;
  }
  const length = request.headers['content-length'];
  if ((length !== undefined && length !== '0') || request.headers['transfer-encoding'] !== undefined) {
    sendError(response, 400, `a ${request.method} request has no body`, { connection: 'close' });
    return;
  }
  const route = context.routes[target.route];
  if (route) {
    await route(response, target.query);
    return;
  }
  const file = await resolveStatic(context.root, target.route === '/' ? '/viewer/index.html' : target.route);
  if (!file) {
    sendError(response, 404, `not one of the viewer's files: ${quoted(target.route)}`);
    return;
  }
  send(response, 200, CONTENT_TYPES[path.extname(file)] ?? 'application/octet-stream', await fs.promises.readFile(file));
}

// The server, not listening yet. `root`: the repository; `toggles`: readFeatureToggles' list;
// `compiler`: a KernelCompiler (or anything with its renderKernel, objectRecordKernel and
// status); `loopbackOnly`: answer only Host headers that name the loopback interface (when
// listening on it); `log`: where errors go, one line each.
export function createViewerServer({ root, toggles, compiler, loopbackOnly = true, log = (line) => console.error(line) }) {
  const context = { root, loopbackOnly, routes: apiRoutes({ root, toggles, compiler }) };
  const server = http.createServer({ connectionsCheckingInterval: LIMITS.checkSeconds * 1000 }, (request, response) => {
    request.on('error', () => {}); // a client that goes away mid-request: nothing to answer
    response.on('error', () => {});
    handle(request, response, context).catch((error) => {
      log(`viewer server: ${request.method} ${quoted(request.url)}: ${error.stack ?? error}`);
      if (response.headersSent) response.destroy();
      else sendError(response, 500, `the server failed on this request: ${error.message}`);
    });
  });
  server.headersTimeout = LIMITS.headersSeconds * 1000;
  server.requestTimeout = LIMITS.requestSeconds * 1000;
  server.maxConnections = LIMITS.connections;
  // What Node's parser refuses (garbage, an unknown method, a header too long) and timeouts.
  server.on('clientError', (error, socket) => {
    if (error.code === 'ECONNRESET' || !socket.writable) {
      socket.destroy();
      return;
    }
    const status = error.code === 'HPE_HEADER_OVERFLOW' ? 431 : error.code === 'ERR_HTTP_REQUEST_TIMEOUT' ? 408 : 400;
    socket.end(`HTTP/1.1 ${status} ${http.STATUS_CODES[status]}\r\nconnection: close\r\ncontent-length: 0\r\n\r\n`);
  });
  server.on('connect', (request, socket) => {
    socket.on('error', () => {});
    socket.end('HTTP/1.1 405 Method Not Allowed\r\nallow: GET, HEAD\r\nconnection: close\r\ncontent-length: 0\r\n\r\n');
  });
  return server;
}
