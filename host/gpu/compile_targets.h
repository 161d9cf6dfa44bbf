// `openpbr compile`: emits the shaders of every target from the single source, e.g.
//   openpbr compile --target all -o build/targets
// writes, per target, Slang's output of the conformance kernel (targets/kernels/conformance.slang)
// and of the consumer example (examples/shade_batch.slang), plus for HLSL the self-contained
// library openpbr.hlsl (targets/hlsl/generate_hlsl.mjs) with its conformance kernel:
//   DIR/spirv/conformance.slang.spv   DIR/spirv/shade_batch.spv
//   DIR/hlsl/conformance.slang.hlsl   DIR/hlsl/shade_batch.hlsl   DIR/hlsl/openpbr.hlsl
//   DIR/hlsl/openpbr_conformance_kernel.hlsl   DIR/hlsl/conformance.hlsl
//   DIR/metal/conformance.slang.metal DIR/metal/shade_batch.metal
//   DIR/cuda/conformance.slang.cu     DIR/cuda/shade_batch.cu
//   DIR/glsl/conformance.slang.glsl   DIR/glsl/shade_batch.glsl
//   DIR/wgsl/conformance.slang.wgsl   DIR/wgsl/shade_batch.wgsl   DIR/wgsl/render.slang.wgsl
//   DIR/wgsl/openpbr.wgsl (the WGSL library, targets/wgsl/generate_wgsl.mjs)
//   DIR/wgsl/conformance.library.wgsl (openpbr.wgsl + targets/wgsl/conformance.wgsl: path wgsl-library)
// With a toggle set (CompileTargetsOptions::feature_mask, `openpbr compile --specialize`) every
// file is specialized when generated: the toggles outside the set compiled out, those inside on,
// none left as a run-time constant (specialization constant, WGSL `override`, Metal function
// constant); host/scene/features.h's specialization_defines. Without one, each target keeps its
// run-time form (docs/specialization.md).
// The Slang compiler is node + targets/slangc.mjs (the Slang 2025.15 WebAssembly build), or a
// native slangc (CMake cache variable OPENPBR_SLANGC). See targets/README.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace openpbr::host {

// The Slang targets, in the order `--target all` emits them.
const std::vector<std::string>& compile_target_names();

struct CompileTargetsOptions
{
    std::vector<std::string> targets;  // e.g. {"spirv", "hlsl"}; "all" = every target
    std::string output_directory;      // e.g. build/targets
    std::string source_directory;      // repository root (slang/, targets/, examples/)
    std::string node = "node";         // runs targets/slangc.mjs and targets/hlsl/generate_hlsl.mjs
    std::string slangc;                // native slangc; empty = node + targets/slangc.mjs
    // Toggles folded when generated (OPENPBR_FEATURE_BIT_*), e.g. scene_feature_mask(materials);
    // unset: every toggle stays a run-time constant.
    std::optional<std::uint32_t> feature_mask;
    // The conformance kernels only (each target's conformance.slang.<ext>, and for WGSL
    // conformance.library.wgsl), e.g. for a check that runs them; false (the default): every file
    // listed above.
    bool conformance_kernels_only = false;
};

// One file written, with the wall time of the command that wrote it.
struct CompiledFile
{
    std::string target;       // e.g. "hlsl"
    std::string description;  // e.g. "conformance kernel (Slang)"
    std::string path;
    std::uintmax_t bytes = 0;
    double seconds = 0.0;
};

// The default source directory and compilers this build was configured with.
CompileTargetsOptions default_compile_targets_options();

// Runs the compilers; throws std::runtime_error naming the failed command.
std::vector<CompiledFile> compile_targets(const CompileTargetsOptions& options);

// One line per file: target, size, seconds, path.
std::string to_text(const std::vector<CompiledFile>& files);

}  // namespace openpbr::host
