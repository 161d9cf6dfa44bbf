// layering_accuracy.h - `openpbr accuracy layering`: the shipped model's own error per material,
// its layering (albedo scaling of lobes, slang/openpbr_bsdf.h) against the layered ground truth
// (host/references/layered_reference.h). docs/layering-accuracy.md has the figures.
//
// Per material and view cosine (the view in the x-z plane, along the tangent):
//   model      the shipped CPU BSDF (float, openpbr_prepare + openpbr_sample): its directional
//              albedo (mean sample weight, host/support/directional_albedo.h), split into
//              reflection and transmission, and its sample weights binned over the reference's
//              direction grid (bin averages of f |cos|, delta lobes included);
//   reference  the same quantities from the layered walk, with standard errors;
//   errors     albedo: per channel model - reference; shape: the total-variation distance
//              between the two distributions of outgoing energy over the grid's bins (Rec. 709
//              luminance of each bin's f |cos| times its solid angle, each normalised to sum 1):
//              1/2 sum_b |p_model,b - p_reference,b|, in [0, 1], the share of the light the
//              model sends to the wrong bins whatever its albedo; with its noise floor (the
//              expected distance of two estimates of one distribution with these standard
//              errors, sqrt(2 / pi) sigma per bin);
//   times      CPU time of the measuring thread (not wall time: the study shares the cores):
//              model: ns per prepare + eval and per prepare + sample (best of 5 batches);
//              reference: ns per path (the estimate's own walks) and the
//              ms one albedo estimate takes at the study's target standard error (0.005 of
//              luminance by default): paths needed = paths x (standard error / target)^2.
// coat_darkening steers the model's approximation, not the physics (spec "Coat", darkening:
// 1 is physical): the model runs at coat_darkening = 1 and the row says so. Every other input
// is used as given (after the input contract both sides share).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/references/layered_reference.h"

namespace openpbr::host {

struct LayeringMaterial
{
    std::string name;   // e.g. "Car Paint" or "metal + coat, ior 2"
    std::string group;  // "bundled" (materials/*.mtlx, user files) or "grid" (the parameter grid)
    OpenPBR_ResolvedInputs inputs;
};

struct LayeringOptions
{
    std::vector<double> view_cosines = {1.0, 0.7, 0.4, 0.15};  // e.g. 1 (normal) to 0.15 (81 degrees)
    std::uint64_t reference_paths = 1u << 17;                  // walks per material and view, e.g. 131072
    std::uint64_t model_samples = 1u << 19;                    // BSDF samples per material and view, e.g. 524288
    std::uint32_t timing_queries = 4096;                       // queries per timing batch, e.g. 4096
    LayeredGrid grid;                                          // 9 x 9 bins per hemisphere
    double target_standard_error = 0.005;  // of the albedo's luminance, for the reference's cost per estimate
    std::uint64_t seed = 1;
    int threads = 0;       // 0: TBB's default (every core); n > 0: at most n
    bool progress = true;  // progress on stderr
};

struct LayeringRow
{
    std::string material;
    std::string group;
    std::string stack;  // the reference's mixture, e.g. "1 coat + glossy-diffuse"
    std::string note;   // what was changed to compare like with like, e.g. "coat_darkening 0.5 -> 1"
    double view_cosine = 1.0;
    LayeredColor model_albedo{}, model_standard_error{}, reference_albedo{}, reference_standard_error{};
    LayeredColor model_reflection{}, reference_reflection{}, reference_reflection_error{};
    double albedo_error = 0.0;           // max over channels of |model - reference| (albedo, R + T)
    double reflection_error = 0.0;       // the same for the reflection alone
    double albedo_error_sigmas = 0.0;    // albedo_error over the combined standard error of that channel (model and
                                         // reference); capped at 1e6 where both are exact (standard error 0)
    double shape_error = 0.0;            // total-variation distance of the binned distributions, [0, 1]
    double shape_noise = 0.0;            // its expected value from noise alone
    double model_ns = 0.0;               // ns per prepare + eval
    double model_sample_ns = 0.0;        // ns per prepare + sample
    double reference_ns = 0.0;           // ns per reference path
    double reference_estimate_ms = 0.0;  // ms per reference albedo estimate at the target standard error
    std::uint64_t reference_paths = 0;
    std::uint64_t capped_paths = 0;
};

// The bundled materials (every .mtlx in the directory, or the given files), group "bundled".
// Throws MaterialError (host/scene/material_library.h) for unreadable files.
std::vector<LayeringMaterial> layering_materials_from_files(const std::vector<std::string>& files);
std::vector<LayeringMaterial> layering_materials_from_directory(const std::string& directory);

// The parameter grid, group "grid": three bases (a copper-coloured metal, an orange
// glossy-diffuse, a clear glass), each under a centre coat (weight 1, IOR 1.6, roughness 0.1,
// clear) varied one axis at a time: coat weight 0 and 0.5, IOR 1.3 and 2, roughness 0, 0.4 and
// 0.8, colour (0.9, 0.6, 0.3); fuzz (roughness 0.5) on the coat and without it; the film (0.4 um,
// IOR 1.4) under the coat and without it.
std::vector<LayeringMaterial> layering_grid_materials();

// Runs every material at every view cosine (in parallel over materials and views; each
// estimate on one thread). Throws std::invalid_argument for empty view cosines or ones outside
// (0, 1].
std::vector<LayeringRow> run_layering_study(const std::vector<LayeringMaterial>& materials, const LayeringOptions& options);

// {"rows": [...], "summary": {...}}: each row with material, view_cosine, model_albedo,
// reference_albedo, reference_standard_error, shape_error, model_ns, reference_ns and the rest
// of LayeringRow; the summary with the settings, the run time, the worst rows and medians.
nlohmann::json layering_to_json(const std::vector<LayeringRow>& rows, const LayeringOptions& options, double seconds);

// The document as text: one row per line (diffable), the summary indented.
std::string layering_json_text(const nlohmann::json& document);

// A table of the rows, worst albedo error first within each group.
std::string layering_to_text(const std::vector<LayeringRow>& rows);

// The picture strip (docs/layering-accuracy.md): spheres of the given materials under an
// environment, reference | model | scaled difference, one row per material, written as PNG.
struct LayeringPictureOptions
{
    int size = 96;                  // pixels per sphere, e.g. 96
    std::uint64_t samples = 256;    // paths (reference) and samples (model) per pixel, e.g. 256
    double difference_scale = 4.0;  // |reference - model| x this in the difference column, e.g. 4
    std::uint64_t seed = 1;
    int threads = 0;  // 0: TBB's default
};
struct LayeringPictureStats
{
    std::string material;
    double rms_difference = 0.0;  // over the sphere's pixels and channels, linear radiance
    double rms_noise = 0.0;       // the RMS standard error of that difference from sampling
    double seconds = 0.0;
};
std::vector<LayeringPictureStats> write_layering_pictures(const std::string& path,
                                                          const std::vector<LayeringMaterial>& materials,
                                                          const LayeringPictureOptions& options);

}  // namespace openpbr::host
