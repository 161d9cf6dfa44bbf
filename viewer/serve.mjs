#!/usr/bin/env node
// Serves the OpenPBR material viewer on localhost (docs/viewer.md):
//   node viewer/serve.mjs [--port N] [--host H] [--compiles N] [--queue M]
// The page and the repository files it reads (the parameter table, the kernel header, the
// bundled materials) are static; the WGSL and the tables are made here from the sources, so the
// viewer needs Node and `npm ci`, not the C++ build. WebGPU needs a secure context, which
// http://127.0.0.1 and http://localhost are. What is served and what each request gets back:
// viewer/server.mjs. Kernel compiles are child processes; SIGINT, SIGTERM and any other exit of
// this process kill them.
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { readFeatureToggles } from './features.mjs';
import { COMPILER_DEFAULTS, KernelCompiler } from './kernels.mjs';
import { createViewerServer } from './server.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const USAGE = `usage: node viewer/serve.mjs [--port N] [--host H] [--compiles N] [--queue M]
  --port N       port to listen on, 0 for any free one (default 8732)
  --host H       address to listen on (default 127.0.0.1; the loopback addresses answer only
                 Host headers naming loopback)
  --compiles N   kernel compiles running at once (default ${COMPILER_DEFAULTS.maxRunning}; each peaks at about 400 MB)
  --queue M      kernel compiles waiting; one more is answered 503 with Retry-After (default ${COMPILER_DEFAULTS.maxWaiting})`;

function fail(message) {
  console.error(`serve.mjs: ${message}\n${USAGE}`);
  process.exit(2);
}

function parseArgs(argv) {
  const options = { port: 8732, host: '127.0.0.1', compiles: COMPILER_DEFAULTS.maxRunning, queue: COMPILER_DEFAULTS.maxWaiting };
  const ranges = { port: [0, 65535], compiles: [1, 64], queue: [0, 1024] };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, '');
    if (!argv[i].startsWith('--') || !(key in options) || i + 1 >= argv.length) fail(`unknown option or missing value at '${argv[i]}'`);
    options[key] = key === 'host' ? argv[i + 1] : Number(argv[i + 1]);
    if (key in ranges && !(Number.isInteger(options[key]) && options[key] >= ranges[key][0] && options[key] <= ranges[key][1])) {
      fail(`--${key} needs an integer in [${ranges[key].join(', ')}] (got '${argv[i + 1]}')`);
    }
  }
  return options;
}

function isLoopback(host) {
  return host === 'localhost' || host === '::1' || /^127\.\d+\.\d+\.\d+$/.test(host);
}

function main() {
  const options = parseArgs(process.argv.slice(2));
  const toggles = readFeatureToggles(path.join(repoRoot, 'slang', 'openpbr_features.h'));
  const compiler = new KernelCompiler(repoRoot, toggles, {
    maxRunning: options.compiles, maxWaiting: options.queue, log: (line) => console.log(line),
  });
  const server = createViewerServer({ root: repoRoot, toggles, compiler, loopbackOnly: isLoopback(options.host) });

  // No compile outlives the server: on a signal (INT, TERM, HUP) the compiles are killed and waited for, then the
  // process exits; on any other exit (an error included) they are killed synchronously.
  process.on('exit', () => compiler.killNow());
  let stopping = false;
  const stop = (signal) => {
    if (stopping) process.exit(1); // a second signal: do not wait
    stopping = true;
    console.log(`OpenPBR viewer: ${signal}, stopping`);
    server.close(); // no new connections; idle ones end
    // The killed and cancelled compiles answer their requests (500, "shutting down"); the
    // connections get a moment to flush, then end.
    compiler.close().then(() => setTimeout(() => {
      server.closeAllConnections();
      process.exit(0);
    }, 200));
  };
  process.on('SIGINT', () => stop('SIGINT'));
  process.on('SIGTERM', () => stop('SIGTERM'));
  process.on('SIGHUP', () => stop('SIGHUP'));

  server.on('error', (error) => {
    console.error(`serve.mjs: cannot listen on ${options.host}:${options.port}: ${error.message}`);
    process.exit(1);
  });
  server.listen(options.port, options.host, () => {
    const { port } = server.address();
    const host = options.host.includes(':') ? `[${options.host}]` : options.host;
    console.log(`OpenPBR viewer: http://${host}:${port}/`);
  });
}

main();
