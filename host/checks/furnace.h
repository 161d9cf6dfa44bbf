// White furnace: the directional albedo of white materials, which must be 1 where the model
// is energy conserving and never above 1 (spec "White furnace testing"; docs/spec-notes.md 12).
// The configuration list is shared by `openpbr furnace` and the statistical test suite
// (tests/bsdf/test_bsdf_statistics.cpp), so the command reports exactly what ctest checks.
#ifndef OPENPBR_HOST_FURNACE_H
#define OPENPBR_HOST_FURNACE_H

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slang/openpbr.h"

namespace openpbr::host {

enum class FurnaceExpectation
{
    // |1 - albedo| <= 0.005 for view cos >= 0.1, and albedo <= 1.005 at every angle.
    energy_conserving,
    // Only albedo <= 1.005 at every angle (white but lossy configurations, e.g. the default
    // material, whose base_color 0.8 absorbs).
    no_energy_gain,
    // The relative-IOR sweep (white dielectric interfaces at every relative IOR, index-matched
    // included): albedo in [0.99, 1.005] at view cos >= 0.1, in [0.97, 1.005] at cos >= 0.02;
    // closer to grazing only the 1.005 bound.
    relative_ior_sweep,
    // The filmed grid (film_furnace_configs): the sweep's bands, albedo in [0.99, 1.005] at view
    // cos >= 0.1, never above 1.005.
    thin_film_grid,
};

enum class FurnaceSide
{
    outside,  // view on the side the geometric normal points to
    inside    // view below the geometric normal (a ray leaving the object)
};

struct FurnaceConfig
{
    std::string name;
    OpenPBR_ResolvedInputs inputs;
    FurnaceExpectation expectation = FurnaceExpectation::energy_conserving;
    std::vector<FurnaceSide> sides = {FurnaceSide::outside};
    // IOR of the medium around the surface (openpbr_prepare's exterior_ior), e.g. 1.33 in water.
    float exterior_ior = 1.0f;
    // Wavelengths (nm) of the RGB channels passed to openpbr_prepare, e.g. {1000, 550, 300} to
    // spread a dispersive IOR over the widest range the input contract accepts.
    vec3 wavelengths_nm = OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM;
    // View cosines of this configuration, e.g. {0.4409} for a view just past a critical angle;
    // empty: white_furnace_view_cosines().
    std::vector<float> view_cosines = {};
};

// The specification's list (white metal; white dielectric with diffuse, subsurface and
// translucent bases; mixes; with a white coat; with white fuzz) plus white glass, white coat
// over a white base, thin-walled glass and IOR 3, at several roughnesses.
const std::vector<FurnaceConfig>& white_furnace_configs();

// The filmed white furnace (the film-under-a-coat grid): a thin film of IOR 1.2, 1.4 or 2 and thickness
// 0.1-1.5 um over a white diffuse base, a white metal and white glass, under no coat or a white
// coat of weight 0.5 or 1 and IOR 1.3, 1.6 or 1.8, coat and specular roughness 0.1, 0.4 or 0.8,
// in air and in water (exterior IOR 1.33), at view cos 1, 0.5 and 0.1: 2268 configurations,
// 6804 rows, each held to the band of FurnaceExpectation::thin_film_grid. Names:
// film_<base>_<coat>_<medium>_n<film IOR>_d<thickness>_r<roughness>, e.g.
// film_diffuse_coat1_ior1p8_air_n1p4_d0p9_r0p4.
const std::vector<FurnaceConfig>& film_furnace_configs();
// View cosines of the furnace, e.g. {1, 0.5, 0.1, 0.02, 0.001}: the tolerance applies from
// 0.1 up, the no-gain bound everywhere.
const std::vector<float>& white_furnace_view_cosines();
// The view cosines a configuration is measured at: its own, or white_furnace_view_cosines().
const std::vector<float>& furnace_view_cosines(const FurnaceConfig& config);

// Tolerances of the white furnace: what a white, energy-conserving material must meet.
constexpr double furnace_tolerance = 0.005;  // |1 - albedo| for cos >= furnace_tolerance_min_cos
constexpr double furnace_tolerance_min_cos = 0.1;
constexpr double furnace_max_albedo = 1.005;  // at every angle

// The relative IORs of the sweep, e.g. 0.67 (glass seen from inside) to 3, 1 included.
const std::vector<float>& furnace_relative_iors();

// Lowest albedo the expectation accepts at view cosine cos_theta (0 where only the no-gain
// bound applies).
double furnace_min_albedo(FurnaceExpectation expectation, float cos_theta);

// Whether one channel's estimate meets the expectation: a gain counts only beyond three
// standard errors of the estimate (albedo - 3 se > furnace_max_albedo), a loss likewise.
bool furnace_albedo_passes(FurnaceExpectation expectation, float cos_theta, double albedo, double standard_error);

// A row of the relative-IOR sweep that does not meet the sweep's band, with the band it is held
// to instead: the measured range of its albedo (every channel, 65536 and 2^20 samples per row)
// widened by its noise. docs/known-limits.md lists them and why.
struct FurnaceKnownLimit
{
    const char* row;  // configuration name with "_inside" for the inside view
    float cos_theta;  // e.g. 0.02; any_view_cosine: every view cosine of the row
    double min_albedo;
    double max_albedo;
};
constexpr float any_view_cosine = -1.0f;
const std::vector<FurnaceKnownLimit>& furnace_known_limits();

// The band [min, max] a row is held to: its known limit where it has one, otherwise
// [furnace_min_albedo, furnace_max_albedo].
struct FurnaceBand
{
    double min_albedo = 0.0;
    double max_albedo = furnace_max_albedo;
    bool known_limit = false;
};
FurnaceBand furnace_band(const FurnaceConfig& config, FurnaceSide side, float cos_theta);
bool furnace_albedo_within(const FurnaceBand& band, double albedo, double standard_error);

// The world-space view of a configuration at local cosine `cos_theta` (azimuth fixed so
// anisotropic configurations see an oblique azimuth), from the given side.
vec3 furnace_view(const OpenPBR_ResolvedInputs& inputs, float cos_theta, FurnaceSide side);

struct FurnaceEstimate
{
    double albedo[3] = {0.0, 0.0, 0.0};  // mean sample weight per channel
    double standard_error[3] = {0.0, 0.0, 0.0};
    double max_weight = 0.0;
    std::uint64_t samples = 0;
};

// Mean of openpbr_sample weights (diffuse + specular, delta samples included, no sample = 0)
// from `samples` independent samples (SplitMix64 counter-based streams, TBB-parallel with a
// deterministic reduction, so the same seed gives the same bits on every run): the
// host's one directional-albedo estimator (host/support/directional_albedo.h).
FurnaceEstimate estimate_furnace_albedo(const OpenPBR_ResolvedInputs& inputs, const vec3& view_world, std::uint64_t samples,
                                        std::uint64_t seed, float exterior_ior = 1.0f,
                                        const vec3& wavelengths_nm = OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM);

struct FurnaceOptions
{
    std::uint64_t samples = 1u << 20;  // per configuration, view and side, e.g. 1048576
    std::string name_filter;           // substring of the configuration name; empty = all
    // Further substrings, e.g. {"film_diffuse_nocoat_air_n1p2_d0p1", "film_metal_coat1"}: a
    // configuration runs when its name contains name_filter (if set) and, if this list is not
    // empty, one of these; one pass, so GPU paths build their pipeline once for all of them.
    std::vector<std::string> name_filters;
    // Paths to run, e.g. {"cpu", "slang-spirv"}: "cpu" is the CPU build (estimate_furnace_albedo);
    // any other name is a GPU path of the conformance kernel, run through the stability runner
    // (host/checks/stability.h: random u, the mean of the sample weights). Empty = {"cpu"}.
    std::vector<std::string> paths;
    std::string kernel_directory;  // compiled kernels for GPU paths, e.g. build/kernels
    // Run the filmed grid (film_furnace_configs) instead of white_furnace_configs, e.g. true
    // for `openpbr furnace --film`.
    bool film_grid = false;
};

struct FurnaceRow
{
    std::string path = "cpu";  // "cpu" or the GPU path, e.g. "slang-spirv"
    std::string name;          // configuration name, "_inside" appended for the inside view
    float cos_theta = 1.0f;
    FurnaceEstimate estimate;
    bool within_tolerance = true;  // the configuration's expectation holds at this view
    bool known_limit = false;      // held to a band of furnace_known_limits()
};

// GPU paths take the rows at the default wavelengths (the conformance kernel's queries carry
// none, so the dispersive rows stay CPU-only), and the standard error of a GPU row is that of its
// largest channel, for every channel. A GPU path that cannot run here (no device) gives no rows
// and is listed in `skipped` with the reason, when given.
std::vector<FurnaceRow> run_white_furnace(const FurnaceOptions& options, std::vector<std::string>* skipped = nullptr);

// {"configs": [{"name": s, "cos_theta": c, "albedo": [r, g, b], "standard_error": [...],
//  "max_weight": w, "samples": n, "pass": b}], "tolerance": ..., "max_albedo": ...}
nlohmann::json furnace_to_json(const std::vector<FurnaceRow>& rows);
std::string furnace_to_text(const std::vector<FurnaceRow>& rows);

}  // namespace openpbr::host

#endif
