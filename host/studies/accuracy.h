// accuracy.h - `openpbr bench accuracy`: what each accuracy knob of the BSDF costs in time,
// measured in one run (docs/accuracy-vs-time.md has the results and the recommendations).
//
// Every setting of every knob gets an error and a time:
//   knobs   energy compensation (none / analytic fit / tables at 16, 32, 64), table storage
//           (compiled-in array, float32 buffer, 16-bit values, texture with hardware filtering on
//           lavapipe), fast-math hooks, visible-normal sampling (Heitz 2018 / spherical caps /
//           bounded VNDF), thin film (full / fast), precision (C++ float / double), baselines
//           (bare real-time GGX with Schlick-Smith or height-correlated visibility, split-sum
//           IBL with DFG tables at 4, 16, 64, 256 samples);
//   errors  directional albedo against the microsurface random walk (host/tables/microsurface.h,
//           cached), max and mean over roughness x cos theta x F0 of a Schlick conductor (F0 in
//           place of the IOR axis: the compensation is the same for every Fresnel); white
//           furnace deviation (white metal and white glass); per-query relative error against
//           the shipped build and against the double-precision build (tools/make_double_headers.py);
//           the variance of the albedo estimator (sampling); bit differences between array and
//           buffer tables (must be 0);
//   times   CPU ns per prepare + eval and per prepare + sample (one thread, the best of 15 rounds
//           that each time every variant, best of three runs per round),
//           and, with `compile`, the Slang compile time and SPIR-V size of the conformance kernel
//           with the setting's defines and that kernel's queries/s on lavapipe (with its
//           per-query error against the CPU build).
// Output: {"rows": [{"knob", "setting", "error_metric", "error", "time_metric", "time"}]},
// CSV with the same columns, and an SVG plot of albedo error against ns per eval on log axes
// with the Pareto front.
#pragma once

#include <cstdint>
#include <filesystem>
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
    // Ground-truth and table cache, e.g. build/accuracy-cache; empty: no cache.
    std::filesystem::path cache_directory;
    // Slang compile time, SPIR-V size and lavapipe queries/s per setting (needs node, the
    // repository and a Vulkan device); off in quick mode.
    bool compile = true;
    std::filesystem::path repository_root;  // for targets/slangc.mjs and the kernel, e.g. "."
    bool progress = true;                   // progress bar on stderr

    // The options with the --quick reductions applied.
    AccuracyOptions effective() const;
};

struct AccuracyRow
{
    std::string knob;
    std::string setting;
    std::string error_metric;
    double error = 0.0;
    std::string time_metric;
    double time = 0.0;
    bool plotted = false;  // the primary pair (albedo error max vs ns per eval) shown in the plot
};

// Runs the study. Throws std::runtime_error on failures (e.g. an unwritable cache).
std::vector<AccuracyRow> run_accuracy_study(const AccuracyOptions& options);

nlohmann::json accuracy_to_json(const std::vector<AccuracyRow>& rows);
std::string accuracy_to_csv(const std::vector<AccuracyRow>& rows);
std::string accuracy_to_text(const std::vector<AccuracyRow>& rows);
// Log-log plot of the plotted rows (albedo error against time) with the Pareto front (the
// settings no other setting beats in both error and time) joined by a line.
std::string accuracy_to_svg(const std::vector<AccuracyRow>& rows);
// Indices (into rows) of the Pareto-optimal plotted rows, sorted by time.
std::vector<std::size_t> accuracy_pareto_front(const std::vector<AccuracyRow>& rows);

// Split-sum DFG table (Karis 2013) of `size` x `size` texels over (n.v, roughness) in [0, 1]^2
// (texel centres at the node coordinates i / (size - 1)), `samples` Hammersley samples per
// texel of openpbr_baseline_dfg_sample; returns (A, B) interleaved.
std::vector<float> generate_dfg_table(int size, std::uint32_t samples, int visibility);

}  // namespace openpbr::host
