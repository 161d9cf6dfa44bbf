// WGSL for the viewer, generated on request from the Slang sources with targets/slangc.mjs (the
// Slang WebAssembly compiler in Node, one child process per compile; no C++ build): the render
// kernel of `openpbr render` (targets/kernels/openpbr_render_kernel.h) as its three step entry
// points (targets/kernels/render_steps.slang) in one module, specialized to a feature set, and
// the material analysis kernel (viewer/object_record.slang).
// Compiles queue with a bound: at most `maxRunning` run at once (a compile peaks at about
// 400 MB and one core) and `maxWaiting` wait; a request beyond that is refused at once with a
// QueueFullError that says when to retry. Requests for a kernel already compiling or waiting
// share that compile. Results are kept, the `maxCached` most recently used of them. close()
// kills every running compile and refuses the waiting ones.
import { execFile } from 'node:child_process';
import path from 'node:path';

import { featureSetLabel, specializationDefines } from './features.mjs';

const RENDER_ENTRIES = ['render_begin_main', 'render_step_main', 'render_end_main'];

// A compile refused because the queue is full; `retryAfterSeconds` is the estimated wait.
export class QueueFullError extends Error {
  constructor(message, retryAfterSeconds) {
    super(message);
    this.retryAfterSeconds = retryAfterSeconds;
  }
}

export const COMPILER_DEFAULTS = {
  maxRunning: 1, // compiles running at once, e.g. 2 on a machine with cores and memory to spare
  maxWaiting: 4, // compiles waiting for a slot; one more is refused (HTTP 503), e.g. 8
  maxCached: 32, // compiled kernels kept (about 230 KB of WGSL each), e.g. 64
  timeoutSeconds: 300, // a compile running longer is killed and fails, e.g. 600
  // The program and arguments of a compile, from the job ({ key, label, source, entries,
  // defines }) and the slangc.mjs arguments; null: node targets/slangc.mjs. A stand-in, e.g.
  // (job, args) => [process.execPath, ['-e', 'setTimeout(() => {}, 60000)']], lets a test hold
  // compiles open without the compiler's cost.
  command: null,
  log: () => {}, // one line per compile started, finished or failed, e.g. console.log
};

export class KernelCompiler {
  constructor(repoRoot, toggles, options = {}) {
    this.repoRoot = repoRoot;
    this.toggles = toggles;
    this.options = { ...COMPILER_DEFAULTS, ...options };
    this.cached = new Map(); // key -> { code, seconds }, least recently used first
    this.pending = new Map(); // key -> { promise, label, job } for compiles running or waiting
    this.waiting = []; // jobs in arrival order
    this.running = new Map(); // key -> { child, label, started }
    this.lastSeconds = 10; // the last compile's duration: the estimate of Retry-After
    this.closed = false;
  }

  // The render kernel with only the toggles of `mask` compiled in.
  renderKernel(mask) {
    return this.compile(`render-${mask}`, `render kernel {${featureSetLabel(this.toggles, mask)}}`,
      'targets/kernels/render_steps.slang', RENDER_ENTRIES, specializationDefines(this.toggles, mask));
  }

  // Every feature on, as constants: the analysis must see every input.
  objectRecordKernel() {
    return this.compile('object_record', 'material analysis kernel', 'viewer/object_record.slang', ['object_record_main'],
      ['OPENPBR_SPECIALIZATION_CONSTANTS=0']);
  }

  // Whether the kernel of `key` is compiled and kept (served without a compile).
  has(key) {
    return this.cached.has(key);
  }

  // A promise of { code, seconds }; a failed compile rejects with the compiler's message and is
  // not kept (the next request tries again). Throws QueueFullError when the queue is full.
  compile(key, label, source, entries, defines) {
    if (this.closed) return Promise.reject(new Error('the server is shutting down'));
    const done = this.cached.get(key);
    if (done) {
      this.cached.delete(key); // re-inserted last: most recently used
      this.cached.set(key, done);
      return Promise.resolve(done);
    }
    const shared = this.pending.get(key);
    if (shared) {
      shared.job.requests += 1;
      return shared.promise;
    }
    const { maxRunning, maxWaiting } = this.options;
    if (this.running.size >= maxRunning && this.waiting.length >= maxWaiting) {
      throw new QueueFullError(`${label}: ${this.running.size} compile(s) running and ${this.waiting.length} waiting, the most this server takes`,
        this.retryAfterSeconds());
    }
    let job;
    const promise = new Promise((resolve, reject) => {
      job = { key, label, source, entries, defines, resolve, reject, requests: 1 };
    });
    promise.catch(() => {}); // every caller awaits it; this keeps a refusal from being "unhandled"
    this.pending.set(key, { promise, label, job });
    this.waiting.push(job);
    this.startWaiting();
    return promise;
  }

  retryAfterSeconds() {
    const rounds = Math.ceil((this.waiting.length + 1) / this.options.maxRunning);
    return Math.min(600, Math.max(1, Math.ceil(rounds * this.lastSeconds)));
  }

  startWaiting() {
    while (!this.closed && this.running.size < this.options.maxRunning && this.waiting.length > 0) {
      this.start(this.waiting.shift());
    }
  }

  start(job) {
    const args = [
      path.join(this.repoRoot, 'targets', 'slangc.mjs'), '-q', '-target', 'wgsl',
      ...job.entries.flatMap((entry) => ['-entry', entry]), '-stage', 'compute',
      '-I', path.join(this.repoRoot, 'slang'), ...job.defines.flatMap((define) => ['-D', define]),
      path.join(this.repoRoot, job.source),
    ];
    const [program, programArgs] = this.options.command?.(job, args) ?? [process.execPath, args];
    const started = performance.now();
    const options = { maxBuffer: 64 << 20, timeout: this.options.timeoutSeconds * 1000, killSignal: 'SIGKILL' };
    const child = execFile(program, programArgs, options, (error, stdout, stderr) => {
      this.running.delete(job.key);
      this.pending.delete(job.key);
      const seconds = (performance.now() - started) / 1000;
      if (error) {
        const why = this.closed ? 'stopped: the server is shutting down'
          : error.killed ? `killed after ${seconds.toFixed(0)} s (the limit is ${this.options.timeoutSeconds} s)`
            : stderr.trim() || error.message;
        this.options.log(`compile ${job.label} failed after ${seconds.toFixed(1)} s`);
        job.reject(new Error(`compiling the ${job.label} failed (slangc.mjs ${job.source} ${job.defines.map((d) => `-D ${d}`).join(' ')}):\n${why}`));
      } else {
        this.lastSeconds = seconds;
        this.keep(job.key, { code: stdout, seconds });
        this.options.log(`compile ${job.label} done in ${seconds.toFixed(1)} s`);
        job.resolve(this.cached.get(job.key));
      }
      this.startWaiting();
    });
    this.running.set(job.key, { child, job, started });
    this.options.log(`compile ${job.label} started (pid ${child.pid})`);
  }

  keep(key, result) {
    this.cached.set(key, result);
    while (this.cached.size > this.options.maxCached) this.cached.delete(this.cached.keys().next().value);
  }

  // What runs and waits, for GET /api/compiles: labels, the requests that share each compile,
  // pids and seconds so far.
  status() {
    const now = performance.now();
    return {
      running: [...this.running.values()].map(({ child, job, started }) => ({
        label: job.label, requests: job.requests, pid: child.pid, seconds: (now - started) / 1000,
      })),
      waiting: this.waiting.map((job) => ({ label: job.label, requests: job.requests })),
      cached: this.cached.size,
      limits: { running: this.options.maxRunning, waiting: this.options.maxWaiting, cached: this.options.maxCached },
    };
  }

  // Refuses the waiting compiles and kills the running ones; resolves once every child has
  // exited. killNow() is the synchronous form for process 'exit' handlers.
  close() {
    this.closed = true;
    for (const job of this.waiting.splice(0)) {
      this.pending.delete(job.key);
      job.reject(new Error(`compiling the ${job.label} was cancelled: the server is shutting down`));
    }
    const exits = [...this.running.values()].map(({ child }) => new Promise((resolve) => {
      if (child.exitCode !== null || child.signalCode !== null) resolve();
      else child.once('exit', resolve);
    }));
    this.killNow();
    return Promise.all(exits);
  }

  killNow() {
    this.closed = true;
    for (const { child } of this.running.values()) {
      if (child.exitCode === null && child.signalCode === null) child.kill('SIGKILL');
    }
  }
}
