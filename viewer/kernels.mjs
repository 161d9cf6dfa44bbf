// WGSL for the viewer, generated on request from the Slang sources with targets/slangc.mjs (the
// Slang WebAssembly compiler in Node; no C++ build): the render kernel of `openpbr render`
// (targets/kernels/openpbr_render_kernel.h) as its three step entry points
// (targets/kernels/render_steps.slang) in one module, specialized to a feature set, and the
// material analysis kernel (viewer/object_record.slang). Each result is kept for the server's lifetime; compiles
// run one at a time (the compiler peaks at about 400 MB).
import { execFile } from 'node:child_process';
import path from 'node:path';

import { specializationDefines } from './features.mjs';

const RENDER_ENTRIES = ['render_begin_main', 'render_step_main', 'render_end_main'];

export class KernelCompiler {
  constructor(repoRoot, toggles) {
    this.repoRoot = repoRoot;
    this.toggles = toggles;
    this.results = new Map();
    this.queue = Promise.resolve();
  }

  // The render kernel with only the toggles of `mask` compiled in.
  renderKernel(mask) {
    return this.compile(`render-${mask}`, 'targets/kernels/render_steps.slang', RENDER_ENTRIES,
      specializationDefines(this.toggles, mask));
  }

  // Every feature on, as constants: the analysis must see every input.
  objectRecordKernel() {
    return this.compile('object_record', 'viewer/object_record.slang', ['object_record_main'],
      ['OPENPBR_SPECIALIZATION_CONSTANTS=0']);
  }

  // Resolves to { code, seconds }; a failed compile rejects with the compiler's message.
  compile(key, source, entries, defines) {
    if (!this.results.has(key)) {
      const run = () => this.runSlangc(source, entries, defines);
      const result = this.queue.then(run, run);
      this.queue = result.catch(() => {});
      this.results.set(key, result);
      // A failure is reported once, not cached: the next request tries again.
      result.catch(() => this.results.delete(key));
    }
    return this.results.get(key);
  }

  runSlangc(source, entries, defines) {
    const args = [
      path.join(this.repoRoot, 'targets', 'slangc.mjs'), '-q', '-target', 'wgsl',
      ...entries.flatMap((entry) => ['-entry', entry]), '-stage', 'compute',
      '-I', path.join(this.repoRoot, 'slang'), ...defines.flatMap((define) => ['-D', define]),
      path.join(this.repoRoot, source),
    ];
    const start = performance.now();
    return new Promise((resolve, reject) => {
      execFile(process.execPath, args, { maxBuffer: 64 << 20 }, (error, stdout, stderr) => {
        if (error) {
          reject(new Error(`slangc.mjs ${source} (${defines.join(' ')}) failed:\n${stderr || error.message}`));
          return;
        }
        resolve({ code: stdout, seconds: (performance.now() - start) / 1000 });
      });
    });
  }
}
