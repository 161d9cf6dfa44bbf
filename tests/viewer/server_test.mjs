#!/usr/bin/env node
// The viewer's server (viewer/serve.mjs, viewer/server.mjs) against malformed and hostile
// requests, on an ephemeral loopback port, without a browser:
// 1. In this process, on a scratch tree: symbolic links out of the page's set (to a file
//    outside the tree, to a file of the tree outside the set, through a linked folder) are not
//    served while a link inside the set is; a handler that throws and a compile that fails are
//    answered 500 and the server goes on; a request whose headers never end gets 408.
// 2. The real server as a child process (`--compiles 1 --queue 2`): one kernel compiled and
//    kept; a burst of distinct feature masks (one running, two waiting, the rest 503 with
//    Retry-After; a repeated mask shares its compile); while they run, bad percent-escapes,
//    encoded and raw '..', NUL, doubled slashes, backslashes, absolute paths and forms, very
//    long paths and headers, odd methods, a GET with a body, a foreign Host, raw garbage on the
//    socket; the page (files, tables, the kept kernel) still loads, byte for byte, before,
//    during and after; then SIGTERM ends the server with status 0, every waiting request is
//    answered, and no compile child outlives it.
// Exit status 0 when every check passes; 1 with the failed checks listed.
// Usage: node tests/viewer/server_test.mjs
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { readFeatureToggles } from '../../viewer/features.mjs';
import { KernelCompiler } from '../../viewer/kernels.mjs';
import { createViewerServer } from '../../viewer/server.mjs';
import { readTableInc } from '../../viewer/tables.mjs';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const toggles = readFeatureToggles(path.join(repoRoot, 'slang', 'openpbr_features.h'));
const REQUEST_LIMIT_MS = 20000; // no answer within this (the server's own header timeout is 15 s): a failure
const failures = [];
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}

// Sends raw bytes on a fresh connection and collects everything until the server closes it:
// { status (null: closed without one), headers, body, timedOut }. `halfClose` ends the sending
// side after the bytes (for garbage, so the server does not wait for more).
function exchange(port, data, { halfClose = false, limitMs = REQUEST_LIMIT_MS } = {}) {
  return new Promise((resolve) => {
    const socket = net.connect(port, '127.0.0.1');
    const chunks = [];
    let timedOut = false;
    const timer = setTimeout(() => {
      timedOut = true;
      socket.destroy();
    }, limitMs);
    socket.on('data', (chunk) => chunks.push(chunk));
    socket.on('error', () => {});
    socket.on('close', () => {
      clearTimeout(timer);
      const raw = Buffer.concat(chunks);
      const split = raw.indexOf('\r\n\r\n');
      const head = (split < 0 ? raw : raw.subarray(0, split)).toString('latin1').split('\r\n');
      const status = /^HTTP\/1\.[01] (\d{3})/.exec(head[0]);
      const headers = Object.fromEntries(head.slice(1).map((line) => [line.slice(0, line.indexOf(':')).toLowerCase(), line.slice(line.indexOf(':') + 1).trim()]));
      resolve({ status: status ? Number(status[1]) : null, headers, body: split < 0 ? Buffer.alloc(0) : raw.subarray(split + 4), timedOut });
    });
    socket.write(data);
    if (halfClose) socket.end();
  });
}

// One request with `connection: close`, the target sent as is.
function request(port, method, target, extraHeaders = '', options = {}) {
  return exchange(port, `${method} ${target} HTTP/1.1\r\nhost: 127.0.0.1:${port}\r\nconnection: close\r\n${extraHeaders}\r\n`, options);
}

const repoFile = (relative) => fs.readFileSync(path.join(repoRoot, relative));

// The page's files as the browser asks for them, each compared with the repository's bytes.
async function checkPage(port, when, keptKernel = null) {
  const wanted = [
    ['/', repoFile('viewer/index.html')], ['/viewer/src/main.mjs', repoFile('viewer/src/main.mjs')],
    ['/viewer/style.css', repoFile('viewer/style.css')], ['/slang/openpbr_parameters.h', repoFile('slang/openpbr_parameters.h')],
    ['/materials/open_pbr_default.mtlx', repoFile('materials/open_pbr_default.mtlx')],
    ['/api/features', Buffer.from(JSON.stringify(toggles))],
    ['/api/tables/fuzz_ltc.bin', readTableInc(path.join(repoRoot, 'slang/generated/openpbr_fuzz_ltc_values.inc'))],
  ];
  if (keptKernel) wanted.push(['/api/kernel/object_record.wgsl', keptKernel]);
  const answers = await Promise.all(wanted.map(([target]) => request(port, 'GET', target)));
  const wrong = wanted.filter(([, bytes], i) => answers[i].status !== 200 || !answers[i].body.equals(bytes)).map(([target], i) => `${target} (${answers[i].status})`);
  const head = await request(port, 'HEAD', '/');
  check(wrong.length === 0 && head.status === 200 && head.body.length === 0 && Number(head.headers['content-length']) === wanted[0][1].length,
    `${when}: the page's ${wanted.length} files${keptKernel ? ' (the kept kernel among them)' : ''} come back byte for byte, HEAD / without a body${wrong.length ? `; wrong: ${wrong.join(', ')}` : ''}`);
}

// Targets sent as is, each with the status it must get; none may be 200.
const HOSTILE_TARGETS = [
  ['/%', 400], ['/%zz/index.html', 400], ['/viewer/%E0%A4%A', 400], ['/viewer/%C0%AE%C0%AE/serve.mjs', 400],
  ['/%2e%2e/%2e%2e/%2e%2e/etc/passwd', 404], ['/viewer/src/%2e%2e/%2e%2e/CMakeLists.txt', 404],
  ['/viewer/src/%2E%2E/serve.mjs', 404], ['/viewer/src/../serve.mjs', 404], ['/../../../../etc/passwd', 404],
  ['/materials/%2e%2e/README.md', 404], ['/viewer/src/..%2f..%2fCMakeLists.txt', 400], ['/materials/..%5c..%5cREADME.md', 400],
  ['/viewer\\index.html', 400], ['/viewer/index.html%00', 400], ['/viewer/index.html%00.png', 400], ['/materials/%00/../README.md', 400],
  ['//etc/passwd', 404], ['/viewer//index.html', 404], ['///', 404], ['/viewer/./index.html', 404], ['/viewer/src/', 404],
  ['/etc/passwd', 404], ['/%2fetc%2fpasswd', 400], ['/.git/config', 404], ['/materials/.hidden', 404],
  ['/node_modules/puppeteer-core/package.json', 404], ['/viewer/serve.mjs', 404], ['/README.md', 404],
  ['*', 400], ['http://127.0.0.1/viewer/index.html', 400], ['viewer/index.html', 400],
  ['/api/kernel/render.wgsl', 400], ['/api/kernel/render.wgsl?features=-1', 400], ['/api/kernel/render.wgsl?features=1e1', 400],
  ['/api/kernel/render.wgsl?features=0x1', 400], ['/api/kernel/render.wgsl?features=99999999999', 400],
  [`/api/kernel/render.wgsl?features=${2 ** 31}`, 400], ['/api/tables/../lut.bin', 404], ['/api/tables/secret', 404], ['/api/nothing', 404],
  [`/${'a/'.repeat(1500)}`, 414],
];

async function sendHostile(port) {
  const answers = await Promise.all(HOSTILE_TARGETS.map(([target]) => request(port, 'GET', target)));
  const wrong = HOSTILE_TARGETS.filter(([, status], i) => answers[i].status !== status)
    .map(([target, status], i) => `${target.slice(0, 60)} got ${answers[i].status}, not ${status}`);
  check(wrong.length === 0, `${HOSTILE_TARGETS.length} malformed and hostile paths get 400, 404 or 414 (encoded '..', NUL, doubled slashes, backslashes, absolute forms)${wrong.length ? `: ${wrong.join('; ')}` : ''}`);

  const methods = ['POST', 'PUT', 'DELETE', 'OPTIONS', 'TRACE', 'PATCH', 'PROPFIND'];
  const methodAnswers = await Promise.all(methods.map((method) => request(port, method, '/', 'content-length: 5\r\n\r\nhello')));
  const connect = await exchange(port, `CONNECT 127.0.0.1:22 HTTP/1.1\r\nhost: 127.0.0.1:22\r\n\r\n`);
  const brew = await request(port, 'BREW', '/');
  check(methodAnswers.every((a) => a.status === 405 && a.headers.allow === 'GET, HEAD') && connect.status === 405 && brew.status === 400,
    `odd methods: ${methods.join(', ')} and CONNECT get 405 with Allow, an unknown one 400 (${[...methodAnswers, connect, brew].map((a) => a.status).join(' ')})`);

  const longPath = await request(port, 'GET', `/${'x'.repeat(100 * 1024)}`);
  const longHeader = await request(port, 'GET', '/', `x-long: ${'y'.repeat(100 * 1024)}\r\n`);
  const withBody = await request(port, 'GET', '/', 'content-length: 3\r\n\r\nabc');
  const foreignHost = await exchange(port, 'GET / HTTP/1.1\r\nhost: attacker.example:80\r\nconnection: close\r\n\r\n');
  check(longPath.status === 431 && longHeader.status === 431 && withBody.status === 400 && foreignHost.status === 403,
    `a 100 KB path and a 100 KB header get 431, a GET with a body 400, a foreign Host 403 (${longPath.status} ${longHeader.status} ${withBody.status} ${foreignHost.status})`);

  // Raw garbage: fixed pseudo-random bytes (a linear congruential generator), a TLS hello, bare
  // line ends, a request cut short, a bad header.
  let seed = 12345;
  const byte = () => {
    seed = (seed * 1103515245 + 12345) % 2147483648;
    return seed >> 16 & 255;
  };
  const garbage = Array.from({ length: 24 }, (_, i) => Buffer.from(Array.from({ length: 1 + ((i * 997) % 3000) }, byte)));
  garbage.push(Buffer.from([0x16, 0x03, 0x01, 0x02, 0x00, 0x01, 0x00, 0x01, 0xfc, 0x03, 0x03]), Buffer.from('\r\n\r\n\r\n'),
    Buffer.from('GET /viewer/index.ht'), Buffer.from('GET / HTTP/1.1\r\nhost: 127.0.0.1\r\ncontent-length: abc\r\n\r\n'),
    Buffer.from('GET / HTTP/9.9\r\n\r\n'), Buffer.from('GET /\0 HTTP/1.1\r\n\r\n'));
  const garbageAnswers = await Promise.all(garbage.map((data) => exchange(port, data, { halfClose: true })));
  check(garbageAnswers.every((a) => !a.timedOut && (a.status === null || (a.status >= 400 && a.status < 500))),
    `${garbage.length} pieces of raw garbage get a 4xx or a closed connection, none hangs (${[...new Set(garbageAnswers.map((a) => a.status ?? 'closed'))].join(', ')})`);
}

function alive(pid) {
  try {
    process.kill(pid, 0);
  } catch {
    return false;
  }
  try {
    return !/^\d+ \(.*\) Z/.test(fs.readFileSync(`/proc/${pid}/stat`, 'utf8')); // a zombie has ended
  } catch {
    return true;
  }
}

async function waitFor(predicate, limitMs) {
  const end = Date.now() + limitMs;
  while (!predicate() && Date.now() < end) await new Promise((resolve) => setTimeout(resolve, 100));
  return predicate();
}

function startServer() {
  const child = spawn(process.execPath, [path.join(repoRoot, 'viewer', 'serve.mjs'), '--port', '0', '--compiles', '1', '--queue', '2'],
    { stdio: ['ignore', 'pipe', 'inherit'] });
  const lines = [];
  const ready = new Promise((resolve, reject) => {
    child.on('exit', (code) => reject(new Error(`viewer/serve.mjs exited (${code}) before listening`)));
    child.stdout.on('data', (data) => {
      lines.push(...String(data).split('\n').filter(Boolean));
      const match = /http:\/\/127\.0\.0\.1:(\d+)\//.exec(lines.join('\n'));
      if (match) resolve(Number(match[1]));
    });
  });
  return { child, lines, ready };
}

const compilePids = (lines) => lines.map((line) => /started \(pid (\d+)\)/.exec(line)).filter(Boolean).map((match) => Number(match[1]));

// The burst: distinct masks at once; answers of the refused come back, the accepted stay open.
async function burst(port) {
  const masks = [1, 2, 3, 4, 5, 6, 7, 8];
  const burstStart = Date.now();
  const pending = masks.map((mask) => ({ mask, answer: null }));
  const finished = pending.map((entry) => request(port, 'GET', `/api/kernel/render.wgsl?features=${entry.mask}`, '', { limitMs: 600000 })
    .then((answer) => { entry.answer = answer; }));
  await waitFor(() => pending.filter((entry) => entry.answer).length >= masks.length - 3, REQUEST_LIMIT_MS);
  const refused = pending.filter((entry) => entry.answer);
  check(refused.length === masks.length - 3 && refused.every((entry) => entry.answer.status === 503 && Number(entry.answer.headers['retry-after']) >= 1),
    `a burst of ${masks.length} distinct masks: ${masks.length - refused.length} accepted (1 running, 2 waiting), ${refused.length} refused with 503 and Retry-After (${refused.map((entry) => `${entry.answer.status}/${entry.answer.headers['retry-after']}`).join(' ')})`);
  const accepted = pending.filter((entry) => !entry.answer);
  const repeated = accepted[accepted.length - 1];
  const shared = request(port, 'GET', `/api/kernel/render.wgsl?features=${repeated.mask}`, '', { limitMs: 600000 });
  const sharedSeen = (status) => [...status.running, ...status.waiting].some((job) => job.requests === 2);
  const compiles = async () => JSON.parse((await request(port, 'GET', '/api/compiles')).body);
  let status = await compiles();
  while (!sharedSeen(status) && Date.now() < burstStart + REQUEST_LIMIT_MS) {
    await new Promise((resolve) => setTimeout(resolve, 100));
    status = await compiles();
  }
  check(status.running.length === 1 && status.waiting.length === 2 && status.running[0].pid > 0 && sharedSeen(status),
    `the queue holds 1 running and 2 waiting compiles, one shared by a repeated request (${[...status.running, ...status.waiting].map((job) => `${job.label} x${job.requests}`).join(', ')})`);
  return { accepted, finished: Promise.all(finished), shared };
}

// Every accepted kernel request ends with an answer (the shared one too: not a 503).
async function checkAnswered(when, { accepted, finished, shared }) {
  await finished;
  const ends = [...accepted.map((entry) => entry.answer), await shared];
  check(ends.every((answer) => answer && (answer.status === 200 || answer.status === 500)),
    `${when}: each accepted kernel request is answered, the repeated one by its shared compile (${ends.map((answer) => answer?.status).join(' ')})`);
}

// The queue with stand-in compiles (held open until closed; the analysis kernel's finishes at
// once): the kept kernel is served while the queue is full, close() ends every child.
async function testQueue() {
  const compiler = new KernelCompiler(repoRoot, toggles, {
    maxRunning: 1, maxWaiting: 2,
    command: (job) => [process.execPath, ['-e', job.key === 'object_record' ? 'process.stdout.write("// object_record_main")' : 'setTimeout(() => {}, 120000)']],
  });
  const server = createViewerServer({ root: repoRoot, toggles, compiler });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address();
  const kernel = await request(port, 'GET', '/api/kernel/object_record.wgsl');
  check(kernel.status === 200 && kernel.body.toString() === '// object_record_main', `stand-in compiles: a compiled kernel comes back (${kernel.status})`);
  const queued = await burst(port);
  await checkPage(port, 'stand-in compiles, the queue full', kernel.body);
  const pids = compiler.status().running.map((entry) => entry.pid);
  await compiler.close();
  check(pids.length === 1 && !pids.some(alive), `close() ends the running compile (pid ${pids.join(', ')})`);
  await checkAnswered('stand-in compiles closed', queued);
  await new Promise((resolve) => server.close(resolve));
}

// The real server and compiler: the burst, the hostile requests while it compiles, SIGTERM.
async function testRealServer() {
  const { child, lines, ready } = startServer();
  const port = await ready;
  try {
    await checkPage(port, 'fresh server');
    const queued = await burst(port);
    await sendHostile(port);
    await checkPage(port, 'during the compiles, after the hostile requests');
    check(child.exitCode === null, 'the server is still running');

    const seen = compilePids(lines);
    check(seen.length >= 1 && seen.some(alive), `compile children seen (pids ${seen.join(', ')}), one of them running before the stop`);
    child.kill('SIGTERM');
    const exited = await waitFor(() => child.exitCode !== null || child.signalCode !== null, 10000);
    check(exited && child.exitCode === 0, `SIGTERM stops the server with status 0 (${child.exitCode ?? child.signalCode})`);
    const gone = await waitFor(() => !compilePids(lines).some(alive), 5000);
    check(gone, `no compile child outlives the server (alive: ${compilePids(lines).filter(alive).join(', ') || 'none'})`);
    await checkAnswered('the real server stopped', queued);
  } finally {
    if (child.exitCode === null && child.signalCode === null) child.kill('SIGKILL');
  }
}

// A scratch tree with links in and out of the page's set, and a compiler whose kernels fail.
async function testInProcess() {
  const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'openpbr-server-test-'));
  try {
    const root = path.join(scratch, 'repo');
    for (const folder of ['viewer/src', 'materials']) fs.mkdirSync(path.join(root, folder), { recursive: true });
    fs.writeFileSync(path.join(root, 'viewer/index.html'), '<!doctype html>');
    fs.writeFileSync(path.join(root, 'materials/kept.mtlx'), '<materialx/>');
    fs.writeFileSync(path.join(root, 'secret_in_tree.txt'), 'in the tree, not in the set');
    fs.writeFileSync(path.join(scratch, 'secret_outside.txt'), 'outside the tree');
    fs.symlinkSync(path.join(scratch, 'secret_outside.txt'), path.join(root, 'materials/outside.mtlx'));
    fs.symlinkSync('../secret_in_tree.txt', path.join(root, 'materials/in_tree.mtlx'));
    fs.symlinkSync('..', path.join(root, 'materials/up'));
    fs.symlinkSync('../../materials/kept.mtlx', path.join(root, 'viewer/src/linked.mtlx'));
    const compiler = {
      renderKernel: () => { throw new TypeError('a handler bug'); },
      objectRecordKernel: () => Promise.reject(new Error('compiling the material analysis kernel failed:\nerror 1: test')),
      status: () => ({ running: [], waiting: [] }),
    };
    const logged = [];
    const server = createViewerServer({ root, toggles, compiler, log: (line) => logged.push(line) });
    server.headersTimeout = 1000; // checked every LIMITS.checkSeconds (5 s): answered 408 within about 6 s
    await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
    const { port } = server.address();
    const slow = exchange(port, 'GET / HTTP/1.1\r\nhost: 127.0.0.1\r\n'); // headers never finished
    const get = (target) => request(port, 'GET', target);
    const links = await Promise.all(['/materials/outside.mtlx', '/materials/in_tree.mtlx', '/materials/up/secret_in_tree.txt', '/viewer/src/linked.mtlx'].map(get));
    check(links.map((a) => a.status).join(' ') === '404 404 404 200' && links[3].body.toString() === '<materialx/>',
      `links out of the set (outside the tree, in the tree, through a linked folder) get 404, a link inside it 200 (${links.map((a) => a.status).join(' ')})`);
    const thrown = await get('/api/kernel/render.wgsl?features=1');
    const failed = await get('/api/kernel/object_record.wgsl');
    const missingTable = await get('/api/tables/lut.bin');
    const after = await get('/');
    check(thrown.status === 500 && missingTable.status === 500 && logged.length === 2 && logged.every((line) => line.includes('viewer server:')) && after.status === 200,
      `a handler that throws (${thrown.status}) and a table that is missing (${missingTable.status}) get 500 and a log line each (${logged.length}); the server answers after them (${after.status})`);
    check(failed.status === 500 && failed.body.toString().includes('error 1: test'), `a failed compile gets 500 with the compiler's message (${failed.status})`);
    // Checked while the other parts run: the unfinished request gets 408 and its connection ends.
    return slow.then((answer) => {
      check(answer.status === 408 && !answer.timedOut, `a request whose headers never end gets 408 (${answer.status})`);
      server.close();
      fs.rmSync(scratch, { recursive: true, force: true });
    });
  } catch (error) {
    fs.rmSync(scratch, { recursive: true, force: true });
    throw error;
  }
}

async function main() {
  const slowChecked = await testInProcess();
  await testQueue();
  await testRealServer();
  await slowChecked;
  if (failures.length > 0) {
    console.log(`\n${failures.length} check(s) failed:\n  ${failures.join('\n  ')}`);
    process.exit(1);
  }
  console.log('\nall checks passed');
}

main().catch((error) => {
  console.error(`server_test: ${error.stack ?? error}`);
  process.exit(1);
});
