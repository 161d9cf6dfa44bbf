// The CUDA conformance paths ("cuda": the headers through their CUDA backend; "slang-cuda":
// Slang's CUDA output) run in a separate program, openpbr_cuda_conformance (built by
// targets/CMakeLists.txt when nvcc is found), which exchanges raw float32 files with the host:
//   inputs  DIR/queries.f32, DIR/materials.f32, DIR/lut.f32, DIR/fuzz_ltc.f32
//   outputs DIR/cuda.results.f32, DIR/slang-cuda.results.f32 (records of
//           targets/kernels/openpbr_conformance_kernel.h)
// The host compares the results with the CPU build like any GPU path's.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace openpbr::host {

// Writes the input files of a batch (the tables are the shipped ones, as on the Vulkan paths).
void write_conformance_inputs(const std::string& directory, const std::vector<float>& queries,
                              const std::vector<float>& materials);

struct ExternalPathResult
{
    std::string name;  // e.g. "cuda", "slang-cuda", "slang-wgsl"
    bool executed = false;
    std::string note;            // the program's line, e.g. "skipped: no CUDA device (...)"
    std::vector<float> results;  // when executed: OPENPBR_RESULT_FLOATS per query
    // Kernel times the program measured with CUDA events (ns per query, median of 5 after a
    // warm-up): "all" (the conformance kernel), "eval", "sample", "pdf" (prepare plus one).
    std::map<std::string, double> device_ns_per_query;
};

// The program this build knows: the environment variable OPENPBR_CUDA_CONFORMANCE_PROGRAM when
// set (e.g. a build copied to a GPU machine at another path), else the path baked in at
// configure time (empty when nvcc was not found then).
std::string default_cuda_conformance_program();

// Runs the program on a batch in a fresh temporary directory; one entry per CUDA path, in the
// order cuda, slang-cuda. A missing program, no device (exit 77) or an error gives entries with
// executed = false and the reason in note; never throws for those.
std::vector<ExternalPathResult> run_cuda_conformance_program(const std::string& program, const std::vector<float>& queries,
                                                             const std::vector<float>& materials);

// The exchange itself, for any program that speaks it (the CUDA program; the WebGPU dispatcher
// targets/wgsl/dispatch_conformance.mjs run by node): writes the inputs to a fresh temporary
// directory, runs `command_line` with that directory appended as its last argument, and reads
// DIR/<name>.results.f32 of each path that reports "<name>: executed ..." (its device time from
// "= T ns/query"). One entry per name, in that order; never throws for a failing program.
std::vector<ExternalPathResult> run_conformance_program(const std::vector<std::string>& command_line,
                                                        const std::vector<std::string>& path_names,
                                                        const std::vector<float>& queries,
                                                        const std::vector<float>& materials);

}  // namespace openpbr::host
