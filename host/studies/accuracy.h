// accuracy.h - `openpbr bench accuracy`: what each accuracy knob of the BSDF costs in time and
// what it gets wrong, measured in one run (docs/accuracy-vs-time.md has the results).
//
// Each knob family is measured with the metric that fits it, against a reference that isolates
// it (the same model with that part exact), and timed on the workload where it matters:
//   compensation   none / analytic fit / table 0 at 16, 64, 128 (shipped): directional albedo
//                  of a white metal against the same model with E_ggx from a 256 x 256 table
//                  integrated in double (max over roughness x view cosine);
//   table storage  float32 array (shipped) / float32 buffer / 16-bit values: per-query relative
//                  eval error against the float32 values (99th percentile), and bit identity;
//   fast math      precise (shipped) / the OPENPBR_FAST_* hooks: the same against precise math;
//   precision      float (shipped) / double: the same against the double build;
//   thin film      full (shipped) / fast: the film's reflectance against the full film (max
//                  absolute, over films, thicknesses and angles), eval error on filmed materials;
//   film estimate  shipped cuts / coarse cuts / the film at the view only: the estimate against
//                  a dense 128 x 128 average over the lobe's visible normals (max absolute);
//   vndf sampling  spherical caps (shipped) / Heitz 2018 / bounded: a variance knob, by the
//                  efficiency 1 / (variance x time) relative to the shipped setting.
// Times: CPU ns per prepare + eval (or sample) on the family's workload, one thread, every
// setting timed once per round over many rounds (best and median kept); with `gpu`, the Slang
// conformance kernel with the setting's defines timed on lavapipe (Vulkan timestamps) and on
// SwiftShader through Dawn (WebGPU timestamps), paired in the same run.
// Model floors, rows of their own: the compensation model against the microsurface random walk
// (host/tables/microsurface.h, with real-time baselines beside it), and the layering model
// against the layered ground truth, read from `openpbr accuracy layering`'s JSON when present.
// With `pictures_directory`, noise-free picture strips per family (a sphere under one light,
// pixel = eval x cos, per setting, and the film's reflectance of the soap bubble), as float32
// images with a manifest; tools/accuracy_figures.py draws the figures and strips.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace openpbr::host {

struct AccuracyOptions
{
    bool quick = false;                      // small grids and sample counts (a test run in seconds)
    std::uint64_t walk_paths = 1u << 16;     // random-walk paths per ground-truth point, e.g. 65536
    std::uint32_t albedo_samples = 4096;     // BSDF samples per albedo estimate, e.g. 4096
    std::uint32_t timing_queries = 8192;     // queries per timing batch, e.g. 8192
    std::uint32_t table_samples = 1u << 14;  // Monte Carlo samples per node of the 16/64 tables
    int timing_rounds = 15;                  // CPU timing rounds (best and median kept), e.g. 15
    // Ground-truth and table cache, e.g. build/accuracy-cache; empty: no cache.
    std::filesystem::path cache_directory;
    // Device times of the Slang kernel per setting on lavapipe and on SwiftShader (needs node,
    // the repository, a Vulkan device; off in quick mode).
    bool gpu = true;
    // The SwiftShader (WebGPU) rows too: SwiftShader builds each setting's pipeline for 20 s
    // (idle) to 2 min (2 cores at load 20), so they are asked for, e.g. true for the docs' run.
    bool webgpu = false;
    std::filesystem::path repository_root;  // for targets/slangc.mjs and the kernels, e.g. "."
    // `openpbr accuracy layering`'s JSON (the layering model's floor), e.g.
    // docs/layering-accuracy.json; a missing file leaves the floor out with a note.
    std::filesystem::path layering_json;
    // Where the picture strips go (float32 images and manifest.json), e.g.
    // build/accuracy-pictures; empty: no pictures.
    std::filesystem::path pictures_directory;
    bool progress = true;  // progress bar on stderr

    // The options with the --quick reductions applied.
    AccuracyOptions effective() const;
};

// A time over the rounds: the best (least disturbed by other processes) and the median.
struct AccuracyTime
{
    double best = 0.0;
    double median = 0.0;
};

// One setting of a knob family.
struct AccuracySetting
{
    std::string variant;  // the variant's name in accuracy_variants.cmake, e.g. "table_16"
    std::string setting;  // e.g. "table 16x16"
    bool shipped = false;
    bool reference = false;  // the family's reference: error 0 by definition
    // The family's metric (AccuracyFamily::error_metric) and its uncertainty (one standard error,
    // 0 where the metric is noise-free).
    double error = 0.0;
    double error_uncertainty = 0.0;
    std::map<std::string, double> other_errors;  // further metrics by name
    AccuracyTime cpu_ns;                         // AccuracyFamily::time_metric
    std::optional<AccuracyTime> lavapipe_ns;     // device ns per prepare + eval, lavapipe
    std::optional<AccuracyTime> webgpu_ns;       // device ns per prepare + eval, SwiftShader
    bool pareto = false;                         // no other setting of the family is both faster and better
};

struct AccuracyFamily
{
    std::string name;          // e.g. "compensation"
    std::string kind;          // "bias" or "variance"
    std::string error_metric;  // e.g. "white-metal albedo error vs exact E_ggx (max)"
    std::string reference;     // what the errors are measured against
    std::string time_metric;   // e.g. "CPU ns per prepare+eval (metal workload)"
    std::vector<AccuracySetting> settings;
};

// A model floor: the shipped model against a ground truth of the physics it approximates.
struct AccuracyFloorRow
{
    std::string setting;
    double error = 0.0;
    double error_uncertainty = 0.0;
    double time_ns = 0.0;
    std::string time_metric;
};

struct AccuracyFloor
{
    std::string name;          // "compensation" or "layering"
    std::string error_metric;  // e.g. "white-metal albedo error vs random walk (max)"
    std::string reference;
    std::string note;  // e.g. why the floor is absent
    std::vector<AccuracyFloorRow> rows;
    nlohmann::json details;  // e.g. the layering file's per-material summary
};

struct AccuracyReport
{
    std::vector<AccuracyFamily> families;
    std::vector<AccuracyFloor> floors;
    nlohmann::json run;  // options, machine, run time
};

// Runs the study. Throws std::runtime_error on failures (e.g. an unwritable cache).
AccuracyReport run_accuracy_study(const AccuracyOptions& options);

// {"run", "families": [...], "model_floors": {...}, "rows": [flat rows]}.
nlohmann::json accuracy_to_json(const AccuracyReport& report);
// One row per setting and metric: family, setting, metric, value, time metric, time.
std::string accuracy_to_csv(const AccuracyReport& report);
std::string accuracy_to_text(const AccuracyReport& report);
// Marks the settings of each family that no other setting beats in both error and CPU time.
void mark_pareto_front(AccuracyFamily& family);

// Split-sum DFG table (Karis 2013) of `size` x `size` texels over (n.v, roughness) in [0, 1]^2
// (texel centres at the node coordinates i / (size - 1)), `samples` Hammersley samples per
// texel of openpbr_baseline_dfg_sample; returns (A, B) interleaved.
std::vector<float> generate_dfg_table(int size, std::uint32_t samples, int visibility);

}  // namespace openpbr::host
