// Numerical stability on hard cases (docs/stability.md): a corpus of hard inputs
// (tests/data/stability_corpus.json) evaluated by the CPU build and by every GPU path through the
// conformance kernel, checked for non-finite and negative outputs, invalid samples and energy
// gain (mean sample weight above 1).
//
// Corpus format: {"cases": [{"name": s, "description": s, "material": {input: value, ...},
// "view": [x, y, z], "lights": [[x, y, z], ...]}, ...]}. Material inputs are OpenPBR input names
// (supported_input_names()) plus the two rotation extensions specular_anisotropy_rotation and
// coat_anisotropy_rotation (2-vectors, (cos, sin)). Floats are JSON numbers or the strings "nan",
// "inf", "-inf", "denorm" (1e-40) and "-denorm"; colors and vector3 inputs are 3-arrays of those,
// geometry_thin_walled a boolean. Directions need not be normalized and accept the same strings.
// The view goes to openpbr_prepare as written (prepare normalizes it); lights are normalized in
// double precision by the host (eval and pdf take unit directions), and a light that has no
// direction (zero or non-finite) is passed as written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "host/checks/path_verdict.h"
#include "slang/openpbr_resolved_inputs.h"

namespace openpbr::host {

// Every corpus failure: unreadable file, malformed JSON, unknown input name, wrong value type.
// The message names the file, the case and the field.
class StabilityCorpusError : public std::runtime_error
{
  public:
    explicit StabilityCorpusError(const std::string& message) : std::runtime_error(message) {}
    ~StabilityCorpusError() override;
};

struct StabilityCase
{
    std::string name;                        // e.g. "glass_inside_total_internal_reflection"
    std::string description;                 // optional free text from the corpus
    openpbr::OpenPBR_ResolvedInputs inputs;  // spec defaults with the case's overrides, unclamped
    glm::vec3 view{0.0f, 0.0f, 1.0f};        // as written (not normalized)
    float exterior_ior = 1.0f;               // IOR of the medium around the surface, e.g. 1.33 (water)
    std::vector<glm::vec3> lights;           // normalized where they have a direction
    std::vector<std::string> inputs_set;     // input names the case overrides, corpus order
};

// Parses a corpus document; `source` names it in messages (e.g. the file path).
std::vector<StabilityCase> parse_stability_corpus(const nlohmann::json& document, const std::string& source);
std::vector<StabilityCase> load_stability_corpus(const std::string& path);

// The input names a corpus material may set: supported_input_names() plus the two rotations.
std::vector<std::string> stability_input_names();

struct StabilityPathResult;

struct StabilityOptions
{
    // Extra samples per case for the sampling statistics (random u and light, fixed seed).
    // 200000 is the CI default; the recorded run (docs) uses 1000000.
    std::size_t samples_per_case = 200000;
    // Samples per case on GPU paths; 0 = samples_per_case. Every path sees a prefix of the same
    // query stream, so a GPU path with fewer samples checks the first queries the CPU checks.
    std::size_t gpu_samples_per_case = 0;
    std::uint64_t seed = 1;
    std::string kernel_directory;  // compiled kernels (.spv), e.g. build/kernels
    // Paths to run, e.g. {"cpu", "slang-spirv"}; empty = "cpu" and every known GPU path.
    std::vector<std::string> paths;
    bool validation = false;  // Vulkan validation layers
    // Called as each path finishes, executed or not, in report order (the CPU build first), e.g.
    // to print its lines at once: `openpbr stability` writes each path's block as it finishes,
    // so that its output (a log file too) shows the run's progress. Unset: nothing is called.
    std::function<void(const StabilityPathResult&)> on_path_finished;
};

// A query as the conformance kernel sees it, with what it produced: for reproducing a finding.
struct StabilityQueryRecord
{
    std::size_t query = 0;  // index within the case: lights first, then the extra samples
    float view[3] = {0, 0, 0};
    float light[3] = {0, 0, 0};
    float u[3] = {0, 0, 0};
    float outputs[21] = {};  // result slots 0..20 (openpbr_conformance_kernel.h)
    std::string what;        // e.g. "non-finite eval.specular.g"
};

struct StabilityCaseResult
{
    std::string name;
    std::size_t queries = 0;          // lights + samples
    std::size_t samples = 0;          // extra samples used for the statistics below
    std::size_t nonfinite = 0;        // non-finite output values (eval, pdf, sample, emission)
    std::size_t negative = 0;         // negative eval, pdf, weight, sample pdf or emission values
    std::size_t invalid_samples = 0;  // pdf == 0 or lobe type NONE (among the samples)
    std::size_t delta_samples = 0;    // samples from delta lobes
    std::size_t bad_directions = 0;   // samples whose direction is not of unit length (|length - 1| > 1e-3)
    double invalid_sample_fraction = 0.0;
    double max_weight = 0.0;                       // max over samples of the max channel of diffuse + specular weight
    double mean_weight[3] = {0, 0, 0};             // per channel mean of the sample weights (invalid samples count 0)
    double max_mean_weight = 0.0;                  // max channel of mean_weight: the directional albedo estimate
    double mean_weight_standard_error = 0.0;       // of the channel reported in max_mean_weight
    std::vector<StabilityQueryRecord> violations;  // the first few non-finite, negative or non-unit outputs
};

struct StabilityPathResult
{
    std::string name;  // "cpu" or a GPU path, e.g. "slang-spirv"
    bool executed = false;
    std::string note;  // the device, or why the path did not execute
    std::size_t nonfinite = 0;
    std::size_t negative = 0;
    std::size_t bad_directions = 0;
    double max_mean_weight = 0.0;  // over all cases
    std::string max_mean_weight_case;
    double max_weight = 0.0;
    std::string max_weight_case;
    double seconds = 0.0;
    std::size_t validation_messages = 0;
    std::vector<StabilityCaseResult> cases;
};

// openpbr_prepare_volume on the CPU: extinction finite and >= 0, albedo finite in [0, 1],
// anisotropy finite in [-1, 1].
struct StabilityVolumeResult
{
    std::string name;
    bool present = false;
    float extinction[3] = {0, 0, 0};
    float albedo[3] = {0, 0, 0};
    float anisotropy = 0.0f;
    bool ok = true;
};

struct StabilityReport
{
    std::size_t case_count = 0;
    std::size_t samples_per_case = 0;
    std::size_t gpu_samples_per_case = 0;
    std::uint64_t seed = 0;
    std::vector<StabilityPathResult> paths;
    std::vector<StabilityVolumeResult> volumes;
    std::size_t volume_violations = 0;
};

// Whether an executed path found no non-finite or negative output and no sample direction not
// of unit length.
bool stability_path_passes(const StabilityPathResult& path);

// Whether a path fails (stability_path_passes) or a volume check does.
bool has_violations(const StabilityReport& report);

// The run's verdict: the executed paths by stability_path_passes, the volume checks' failures
// first.
PathVerdict stability_verdict(const StabilityReport& report);

// The paths run_stability runs for these options, in report order: options.paths, or "cpu"
// and every known GPU path; an unknown name is an error (std::invalid_argument).
std::vector<std::string> stability_paths(const StabilityOptions& options);

// The corpus on the paths options.paths names: the CPU build and the GPU paths
// (host/checks/execution_path.h), each through the same query stream (stability_paths.cpp).
StabilityReport run_stability(const std::vector<StabilityCase>& cases, const StabilityOptions& options);

// The CPU build alone (options.paths is not read): the report run_stability gives for
// options.paths = {"cpu"}, in a program without the GPU paths (library openpbr_host_core, e.g.
// tests/checks/test_stability_cpu.cpp). include_cpu_path false: the report's header and the
// volume checks only (run_stability, where the paths asked for leave the CPU out).
StabilityReport run_stability_cpu(const std::vector<StabilityCase>& cases, const StabilityOptions& options,
                                  bool include_cpu_path = true);

// One path's batches: queries and packed materials in, results out, laid out as
// run_conformance_cpu's (conformance.h), e.g. run_conformance_cpu itself.
using StabilityExecutor =
    std::function<std::vector<float>(const std::vector<float>& queries, const std::vector<float>& materials)>;
// One path over every case: its samples_per_case queries per case of the stream `seed` gives
// (a pure function of seed, case and query), in batches under lavapipe's storage-buffer range.
StabilityPathResult run_stability_path(const std::string& name, const StabilityExecutor& execute,
                                       const std::vector<StabilityCase>& cases, std::size_t samples_per_case,
                                       std::uint64_t seed);

// JSON: {"cases": N, "samples_per_case": n, "seed": s, "paths": [{"name", "executed", "note",
// "nonfinite", "negative", "max_mean_weight", "max_weight", "cases": [...]}], "volume": {...},
// "verdict": to_json(stability_verdict(report))}.
// Every case counts towards max_mean_weight: emission is not part of the sample weights.
nlohmann::json to_json(const StabilityReport& report);

// The text report in the order `openpbr stability` prints it as the run goes: the header (the
// counts and the seed), each path's block (its line, then a row per case), the volume checks,
// and the verdict line last. to_text(report) is all of them.
std::string stability_header_text(const StabilityReport& report);
std::string to_text(const StabilityPathResult& path);
std::string stability_volume_text(const StabilityReport& report);
std::string to_text(const StabilityReport& report);

// The binary seed inputs of fuzz/fuzz_bsdf.cpp (fuzz/fuzz_input_layout.h), one per case and
// light for the first three lights of each case: "<case>_<light>.bin" in `directory` (created if
// missing), u as in the query stream of seed 1. Returns the file count.
std::size_t write_fuzz_seed_corpus(const std::vector<StabilityCase>& cases, const std::string& directory);

}  // namespace openpbr::host
