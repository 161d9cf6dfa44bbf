// fuzz_fit.h - the reference simulation and the LTC fit behind the fuzz lobe
// (slang/lobes/openpbr_fuzz_lobe.h), and the reading / writing of its shipped table:
//   slang/generated/openpbr_fuzz_ltc_values.inc  comma-separated float literals (array mode)
//   slang/generated/openpbr_fuzz_ltc.bin         raw float32, little-endian, no header (buffer mode)
//
// Model (Zeltner, Burley, Chiang 2022, "Practical Multiple-Scattering Sheen Using Linearly
// Transformed Cosines", SIGGRAPH Talks; OpenPBR 1.1 section "Fuzz"):
//   - a slab of unit thickness holding fiber-like SGGX microflakes (Heitz, Dupuy, Crassin,
//     Dachsbacher 2015, "The SGGX Microflake Distribution") of unit density, fibers along the
//     normal. In Heitz et al.'s parameterization by projected areas, S = diag(1, 1, c^2) in the
//     local frame (z = normal), c the fibers' cross section (their projected area along the
//     normal, relative to 1 across it). The roughness maps to it as alpha = sqrt(c), i.e.
//     c = alpha^2: the authors' public description of their reference layer says "the cross
//     section parameter sigma in [0, 1] is mapped to the roughness as alpha = sqrt(sigma)"
//     (fuzz_cross_section_from_roughness; the one place to change if that reading is wrong).
//   - extinction coefficient = projected area sigma(w) = sqrt(wx^2 + wy^2 + c^2 wz^2) <= 1:
//     "unit optical thickness" is read as unit density x unit thickness, so the optical
//     thickness is 1 for horizontal travel and c along the normal (1 for spherical flakes).
//   - non-absorbing specular flakes: phase function D(h) / (4 sigma(wi)), h the half vector,
//     sampled exactly by reflecting on a visible normal of the SGGX (ellipsoid) distribution.
//   - index-matched boundaries (no Fresnel), a black (fully absorbing) base below.
// Convention: the simulation sends light in along -wo (wo the view direction of the lobe) and
// records the directions wi of the light that leaves through the top. By reciprocity of the
// slab (symmetric phase function, index-matched) the exit density is mu_i f(wi, wo) / R(mu_o),
// and the exiting fraction is the view's directional albedo R(mu_o, alpha).
//
// Fit: the exit directions are binned over (mu_i, |phi_i - phi_o|) on equal-solid-angle bins,
// folded about the plane of incidence (the distribution is mirror-symmetric in y). The LTC
// (Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines") is the paper's two-parameter one, tabulated like Heitz et al. by its
// inverse transform: M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]] (wo in the x-z plane at phi = 0),
// i.e. M = [[1/a, 0, -b/a], [0, 1/a, 0], [0, 0, 1]] (the family is closed under inversion, so
// this is a choice of coordinates only: a grows about linearly with the cross section, which
// bilinear interpolation reproduces well, where the scale of M grows like its inverse). Density:
//   D(w) = a^2 wz / (pi ((a wx + b wz)^2 + a^2 wy^2 + wz^2)^2),  wz > 0,
// and (a, b) minimise the L2 distance between its bin averages and the histogram densities
// (coarse grid search over (log a, b), then Nelder-Mead). At mu_o = 1 the distribution is
// rotationally symmetric and b = 0 exactly.
//
// Grid (node-centred, like slang/openpbr_lut.h): node (i, j) has mu_o = i / (N - 1) and
// alpha = j / (N - 1). The cross section is floored: c = max(alpha^2, 0.01), so the rows with
// alpha <= 0.1 (j = 0..3 of 32) all hold the c = 0.01 layer. At c -> 0 every flake normal is
// horizontal, a specular reflection keeps the vertical component of the direction, and light
// comes back only from exactly grazing incidence, into a lobe that collapses onto the horizon
// (R -> 0 for mu_o > 0, LTC degenerate); c = 0.01 is about the narrowest grazing lobe the
// 32-bin histogram resolves (fitted a >= 0.016).
// Cells where too few photons came back to fit a shape (fewer than fuzz_min_fit_count) take
// (a, b) from the nearest fitted cell of higher alpha in the same mu_o column; their R is kept.
//
// Layout: three 2D channels of N x N floats, channel c at offset c * N * N, index within a
// channel = alpha_index * N + mu_index: channel 0 = a, 1 = b, 2 = R.
//
// Determinism: every cell has its own random stream seeded by a hash of (seed, cell index),
// histograms are integer counts, so the table is independent of the thread count.
// Link dependencies: TBB (CMake: find_package(TBB), target TBB::tbb), GLM (header-only);
// include directory: the repository root.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace openpbr::host {

inline constexpr int fuzz_ltc_channel_count = 3;          // a, b, R
inline constexpr double fuzz_min_cross_section = 0.01;    // c = max(alpha^2, this)
inline constexpr std::uint64_t fuzz_min_fit_count = 256;  // reflected photons needed to fit (a, b)

struct FuzzFitOptions
{
    int size = 32;                     // nodes per axis; the lobe header compiles 32
    std::uint64_t photons = 1u << 19;  // photons per cell (about 3 CPU-minutes in all)
    int histogram_mu_bins = 32;        // bins over mu_i in [0, 1]
    int histogram_phi_bins = 32;       // bins over |phi_i - phi_o| in [0, pi]
    std::uint64_t seed = 0x0F0220F0u;  // base seed of the per-cell streams
    int threads = 0;                   // 0: TBB's default (every core); n > 0: at most n
    bool progress = false;             // progress on stderr: a line per 10% (a bar on a terminal)
};

// Node coordinate -> physical parameter.
double fuzz_mu_from_coordinate(double c);                // c
double fuzz_alpha_from_coordinate(double c);             // c (the roughness, clamped to [0, 1])
double fuzz_cross_section_from_roughness(double alpha);  // max(alpha^2, fuzz_min_cross_section)
std::uint64_t fuzz_cell_seed(std::uint64_t seed, std::size_t cell);

// The microflake medium, exposed for tests, for a cross section c in (0, 1]. Directions are
// unit vectors in the local frame.
double fuzz_sggx_projected_area(const glm::dvec3& w, double cross_section);  // sigma(w)
double fuzz_sggx_normal_density(const glm::dvec3& m, double cross_section);  // D(m), m on the sphere
// A visible normal for direction w (density <w, m>+ D(m) / sigma(w)), from two uniforms.
glm::dvec3 fuzz_sggx_sample_visible_normal(const glm::dvec3& w, double cross_section, double u1, double u2);
// Specular microflake phase function; wi, wo both point away from the scattering point:
// D(h) / (4 sigma(wi)), h = normalize(wi + wo); integrates to 1 over wo.
double fuzz_phase_density(const glm::dvec3& wi, const glm::dvec3& wo, double cross_section);
// Samples wo for wi (both pointing away) with density fuzz_phase_density.
glm::dvec3 fuzz_phase_sample(const glm::dvec3& wi, double cross_section, double u1, double u2);

// Normalised LTC density D(w) for M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]] (0 for wz <= 0).
double fuzz_ltc_density(double a, double b, const glm::dvec3& w);

struct FuzzSimulation
{
    double mu_o = 0.0;
    double cross_section = 0.0;
    std::uint64_t photons = 0;
    std::uint64_t reflected = 0;  // photons that left through the top
    std::uint64_t capped = 0;     // walks stopped after fuzz_max_scattering events (counted absorbed)
    int mu_bins = 0;
    int phi_bins = 0;
    std::vector<std::uint64_t> histogram;  // index = mu_bin * phi_bins + phi_bin

    double reflected_fraction() const { return photons ? double(reflected) / double(photons) : 0.0; }
    // Each bin covers the solid angle 2 pi / (mu_bins phi_bins) (both signs of phi).
    double bin_solid_angle() const;
};

// Random walk of `photons` photons for the view (sqrt(1 - mu_o^2), 0, mu_o), seeded by `seed`,
// in the layer of cross section c (fuzz_cross_section_from_roughness(alpha) for roughness alpha).
FuzzSimulation simulate_fuzz_layer(double mu_o, double cross_section, std::uint64_t photons, int mu_bins, int phi_bins,
                                   std::uint64_t seed);

struct FuzzLtcFit
{
    double a = 1.0;
    double b = 0.0;
    double relative_l2_error = 0.0;  // ||D_ltc - p||_2 / ||p||_2 over the bins (bin averages)
    double total_variation = 0.0;    // 1/2 sum |P_ltc(bin) - P_sim(bin)|: fraction of energy misplaced
    // The part of total_variation expected from the histogram's noise alone (Poisson counts n:
    // E|n - E n| ~ sqrt(2 n / pi)): 1/2 sum sqrt(2 n_bin / pi) / n_reflected.
    double noise_total_variation = 0.0;
    bool fitted = false;  // false: too few reflected photons, (a, b) = (1, 0)
};

// Fits (a, b) to the exit distribution of `simulation`; b is held at 0 when `symmetric`.
FuzzLtcFit fit_fuzz_ltc(const FuzzSimulation& simulation, bool symmetric);
// The error measures of a given (a, b) against a simulation (fills the two error fields).
FuzzLtcFit evaluate_fuzz_ltc(const FuzzSimulation& simulation, double a, double b);

struct FuzzCellReport
{
    double mu_o = 0.0;
    double alpha = 0.0;          // the roughness of the node
    double cross_section = 0.0;  // the simulated layer's c
    double reflected_fraction = 0.0;
    FuzzLtcFit fit;  // as fitted (fit.fitted false: (a, b) filled from a neighbour in the table)
};

// The whole table (fuzz_ltc_channel_count * size^2 floats, layout above). `report`, when not
// null, receives one entry per cell in table order (alpha_index * size + mu_index).
std::vector<float> generate_fuzz_table(const FuzzFitOptions& options, std::vector<FuzzCellReport>* report = nullptr);

// One cell as generate_fuzz_table computes it (without the neighbour fill), e.g. for tests
// that regenerate a few cells at a lower photon count.
FuzzCellReport generate_fuzz_cell(const FuzzFitOptions& options, int mu_index, int alpha_index);

// "%.8e" + "f" per line (round-trips float32, valid GLSL), commas between values, optional
// "//" comment lines first. Written to a temporary name and renamed.
void write_fuzz_values_inc(const std::filesystem::path& path, const std::vector<float>& data,
                           const std::string& comment = std::string());
std::vector<float> read_fuzz_values_inc(const std::filesystem::path& path);
std::vector<float> read_fuzz_binary(const std::filesystem::path& path, std::size_t expected_count = 0);

}  // namespace openpbr::host
