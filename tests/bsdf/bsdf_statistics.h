// Statistical test machinery for the OpenPBR BSDF (C++ build of the single-source headers).
//
// Everything works on a SamplingTarget: a sampler, its pdf and its eval, all in world space,
// plus a frame used to bin directions. make_bsdf_target wraps a prepared BSDF; a single lobe
// can be wrapped the same way (see the reciprocity helpers), so the same tests apply to new
// lobes and to the full BSDF alike.
//
// What is provided:
//  - random numbers: RandomStream (independent samples, SplitMix64) and the shifted R3 sequence
//    (low discrepancy, for integration only: its points are not independent, so chi-square
//    p-values computed from it would be meaningless);
//  - run_chi_square_test: goodness of fit of sample() against pdf() over the full sphere, with
//    delta lobes as discrete atoms and "no sample" as one more cell, on a (cos theta, phi) grid
//    in the surface frame or, for a lobe narrower than its cells, on a polar grid warped around
//    the lobe (SamplingTarget::polar_scale);
//  - check_pdf_integral: integral of pdf() over the sphere against the fraction of valid
//    non-delta samples;
//  - check_sample_consistency: weight == eval / pdf and returned pdf == pdf() per sample;
//  - estimate_albedo: white-furnace / directional-albedo estimate with its standard error;
//  - check_reciprocity: f(wo, wi) / |cos wi| == f(wi, wo) / |cos wo| for one lobe;
//  - numerics: regularized incomplete gamma, chi-square and binomial p-values, Sidak level.
#ifndef OPENPBR_TESTS_BSDF_STATISTICS_H
#define OPENPBR_TESTS_BSDF_STATISTICS_H

#include "host/support/directional_albedo.h"
#include "host/support/random.h"
#include "slang/openpbr.h"

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace openpbr::testing {

// ------------------------------------------------------------------------------------------
// Random numbers

// Independent uniform numbers: the host's one generator, SplitMix64 (host/support/random.h),
// one stream per (seed, stream) pair, its state starting at splitmix64(seed) xor
// splitmix64(~stream): different pairs start at unrelated points of the 2^64 cycle, so the
// streams the tests draw (at most 2^32 numbers each) do not overlap in practice.
class RandomStream
{
  public:
    explicit RandomStream(std::uint64_t seed = 0, std::uint64_t stream = 0);
    // The top 32 bits of the next output.
    std::uint32_t next_uint();
    // Uniform in [0, 1), 24 random bits (every value exactly representable as a float).
    float next_float();
    // Uniform in [0, 1), 53 random bits.
    double next_double();

  private:
    host::SplitMix64 generator_;
};

// The low-discrepancy points of the tests are the accuracy study's: host::ShiftedR3Sequence
// (host/support/directional_albedo.h), Roberts' R3 sequence with a random Cranley-Patterson
// shift per seed, so independent replicas give randomized quasi-Monte Carlo error estimates.

enum class SamplerKind
{
    independent,     // RandomStream
    low_discrepancy  // host::ShiftedR3Sequence; integration only
};

// Float in [0, 1) from a double in [0, 1): rounding to nearest could otherwise give 1.0f.
float to_unit_float(double x);

// A seed from a test name (FNV-1a), the same on every platform, unlike std::hash.
std::uint64_t seed_from_name(const std::string& name);

// ------------------------------------------------------------------------------------------
// What the tests sample

struct DirectionSample
{
    glm::vec3 direction{0.0f};  // world space
    OpenPBR_DiffuseSpecular weight{glm::vec3(0.0f), glm::vec3(0.0f)};
    double pdf = 0.0;  // solid-angle pdf, or the delta lobe's discrete probability
    std::uint32_t lobe_type = OPENPBR_LOBE_TYPE_NONE;

    bool is_valid() const { return lobe_type != OPENPBR_LOBE_TYPE_NONE; }
    bool is_delta() const { return (lobe_type & OPENPBR_LOBE_TYPE_SPECULAR) != 0u; }
    glm::vec3 total_weight() const { return weight.diffuse + weight.specular; }
};

struct SamplingTarget
{
    std::string name;
    // Directions are binned in this frame: polar angle theta from frame.normal, phi from the
    // tangent towards the bitangent. Aligning it with the surface puts a bin edge on the
    // horizon, where pdfs are discontinuous.
    OpenPBR_Basis frame{};
    // How theta is binned. 0: uniformly in cos theta over [-1, 1] (the surface grid). > 0: a
    // warped polar grid for a lobe narrower than a cell of that grid, e.g. 2.4e-3 for the
    // refraction at relative IOR 0.99 and roughness 0.5: frame.normal is the lobe's axis and
    // theta is binned uniformly in s = log(1 + theta / polar_scale) / log(1 + pi / polar_scale),
    // so the cells near the axis are a fraction of polar_scale wide and grow geometrically (by
    // (1 + pi / polar_scale)^(1 / bins), 1.25 for 32 bins at 2.4e-3) out to theta = pi: the
    // whole sphere is still covered.
    double polar_scale = 0.0;
    std::function<DirectionSample(const glm::vec3& u)> sample;
    // The continuous part only (delta lobes are invisible to it), world-space direction.
    std::function<double(const glm::vec3& direction)> pdf;
    // BSDF x |cos|, continuous part only; may be empty when only sampling is tested.
    std::function<OpenPBR_DiffuseSpecular(const glm::vec3& direction)> eval;
    // Expected fraction of delta samples: the selection probability of each delta lobe times
    // its delta_share.
    double delta_probability = 0.0;
    // Per delta lobe id (lobe_type >> OPENPBR_LOBE_ID_SHIFT), the fraction of that lobe's samples
    // that are delta, where it is below 1: a lobe whose delta samples report its selection
    // probability as pdf but which also returns rough or no samples, e.g. the dielectric whose
    // collapsed refraction is a delta event while its reflection stays rough (Fresnel) and whose
    // steepest microfacets reflect totally. Lobes not listed: 1.
    std::map<std::uint32_t, double> delta_share;
};

// Expected fraction of delta samples of the prepared BSDF: the selection probabilities of its
// delta lobes, read from its lobe structs, each times its share of delta samples
// (dielectric_delta_share for a dielectric whose refraction collapsed to a delta event). Must
// be extended whenever a lobe that can be a delta (coat, transmission, ...) is added to
// OpenPBR_PreparedBsdf.
double delta_selection_probability(const OpenPBR_PreparedBsdf& bsdf);

// Fraction of the samples of a dielectric lobe whose refraction is a delta event
// (transmission_is_delta with rough microfacets) that are delta: the visible-normal average of
// (1 - F) (F = 0 for the transmission-only form) where Snell's law refracts below the surface,
// with the distribution of visible normals of Heitz 2014 ("Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs"):
//   share = integral over h of G1(o) max(0, o.h) D(h) / o.n (1 - F(o.h)) [refracts] dh,
// integrated on the warped polar grid around the normal (scale alpha); 1 exactly at eta = 1
// (F = 0 and every microfacet passes the light straight on).
double dielectric_delta_share(const OpenPBR_DielectricLobe& lobe, const glm::vec3& view);

// The prepared BSDF as a target. Where its non-delta refraction is narrower than the
// surface grid's cells (openpbr_dielectric_transmission_width below kNarrowRefractionWidth),
// the grid is the warped polar one (polar_scale) around the refracted lobe, whose axis and
// scale are the mean direction and the median angle from it of a pilot of 4096 refracted
// samples (an independent seed: the cells are fixed before the tested samples are drawn, so the
// chi-square statistic keeps its distribution).
SamplingTarget make_bsdf_target(const OpenPBR_PreparedBsdf& bsdf, const std::string& name = "bsdf");

// A refracted lobe narrower than this (radians) gets the warped grid: the surface grid's
// phi cells are 2 pi / 64 = 0.098 rad wide, and at relative IOR 0.99, roughness 0.5 its
// quadrature integrates 0.198 of a lobe of 2.4e-3 rad (view cos 1) and is off by 4e-4 to 1e-3
// (10 to 120 binomial standard errors at 1e6 samples) for lobes of 8e-3 to 0.04 rad (view cos
// 0.5 to 0.02). Rough glass at view cos 1 (0.03 to 0.08 rad) is on the warped grid as well.
constexpr double kNarrowRefractionWidth = 0.1;

// ------------------------------------------------------------------------------------------
// Numerics

// Regularized lower / upper incomplete gamma functions P(a, x), Q(a, x) = 1 - P(a, x):
// series for x < a + 1, continued fraction (modified Lentz) otherwise.
double regularized_gamma_p(double a, double x);
double regularized_gamma_q(double a, double x);
// P(X >= statistic) for a chi-square variable with `degrees_of_freedom`; 1 for dof <= 0.
double chi_square_p_value(double statistic, int degrees_of_freedom);
// Two-sided p-value of observing `successes` out of `trials` with success probability p:
// the probability of an outcome at most as likely as the observed one (exact sum of the
// binomial pmf when the variance is small, normal approximation otherwise).
double binomial_two_sided_p_value(std::uint64_t successes, std::uint64_t trials, double p);
// Per-test significance so that `test_count` independent tests have a total false-positive
// rate of `family_significance`: 1 - (1 - family_significance)^(1 / test_count).
double sidak_significance(double family_significance, int test_count);

// Gauss-Legendre nodes and weights on [-1, 1] (Newton iteration on the Legendre recurrence).
void gauss_legendre(int order, std::vector<double>& nodes, std::vector<double>& weights);

// ------------------------------------------------------------------------------------------
// Integration of the pdf over the grid: (cos theta, phi), or (warped polar angle, phi)

struct SphereGridOptions
{
    // Over cos theta in [-1, 1] (even, so a bin edge is on the horizon), or over the warped
    // polar coordinate s in [0, 1] when the target has a polar_scale.
    int cos_theta_bins = 32;
    int phi_bins = 64;         // over phi in [0, 2 pi)
    int quadrature_order = 8;  // Gauss-Legendre nodes per axis per (sub)cell
    // Adaptive refinement: a cell is split in 2 x 2 until the split changes its integral by
    // less than max(relative_tolerance * value, absolute_tolerance) or the depth is reached.
    int max_depth = 5;
    double relative_tolerance = 1e-6;
    double absolute_tolerance = 1e-10;
};

// Integral of target.pdf over every cell, cos-theta-major (index = i_theta * phi_bins + i_phi).
std::vector<double> integrate_pdf_over_grid(const SamplingTarget& target, const SphereGridOptions& grid);
// The cell of a world-space direction, same indexing.
int grid_cell_of(const SamplingTarget& target, const SphereGridOptions& grid, const glm::vec3& direction);

// ------------------------------------------------------------------------------------------
// Chi-square goodness of fit of sample() against pdf()

struct ChiSquareOptions
{
    SphereGridOptions grid;
    std::uint64_t sample_count = 1000000;
    std::uint64_t seed = 1;
    double min_expected_count = 5.0;  // cells expecting fewer are pooled (PBRT-style)
    // Delta samples of one lobe must all report the same pdf to this relative precision.
    double delta_pdf_relative_tolerance = 1e-5;
};

// The delta samples of one lobe (one lobe id), expected with the probability they report.
struct DeltaAtom
{
    std::uint32_t lobe_type = 0;  // of the first sample seen
    std::uint64_t count = 0;
    double reported_pdf_min = 0.0;
    double reported_pdf_max = 0.0;
    double reported_pdf_mean = 0.0;
};

struct ChiSquareResult
{
    std::uint64_t sample_count = 0;
    std::uint64_t continuous_count = 0;  // valid non-delta samples
    std::uint64_t delta_count = 0;
    std::uint64_t invalid_count = 0;    // no sample (lobe_type NONE)
    std::uint64_t nonfinite_count = 0;  // samples with non-finite or non-unit directions
    double pdf_integral = 0.0;          // quadrature of pdf() over the sphere
    double delta_probability = 0.0;     // target.delta_probability
    double delta_reported_sum = 0.0;    // sum over the atoms of reported pdf x delta_share
    bool delta_pdfs_consistent = true;  // every atom reports one pdf, and the sum matches
    std::vector<DeltaAtom> atoms;

    double statistic = 0.0;
    int degrees_of_freedom = 0;
    int pooled_cell_count = 0;        // cells merged into the pool
    double p_value = 1.0;             // chi-square
    double delta_p_value = 1.0;       // binomial: delta fraction vs target.delta_probability
    double continuous_p_value = 1.0;  // binomial: continuous fraction vs pdf_integral

    std::vector<double> observed;  // per grid cell
    std::vector<double> expected;  // per grid cell (counts)
    std::string report;            // human-readable summary incl. the worst cells
};

ChiSquareResult run_chi_square_test(const SamplingTarget& target, const ChiSquareOptions& options);

// ------------------------------------------------------------------------------------------
// Integral of the pdf vs the fraction of valid non-delta samples

struct PdfIntegralResult
{
    double pdf_integral = 0.0;
    double valid_fraction = 0.0;  // valid non-delta samples / all samples
    double standard_error = 0.0;  // binomial standard error of valid_fraction
    double p_value = 1.0;         // binomial test of the count against pdf_integral
    std::uint64_t sample_count = 0;
};

PdfIntegralResult check_pdf_integral(const SamplingTarget& target, std::uint64_t sample_count, std::uint64_t seed,
                                     const SphereGridOptions& grid = SphereGridOptions());

// ------------------------------------------------------------------------------------------
// Per-sample consistency of sample(), pdf() and eval()

struct ConsistencyOptions
{
    std::uint64_t sample_count = 100000;
    std::uint64_t seed = 7;
    SamplerKind sampler = SamplerKind::independent;
    double relative_tolerance = 1e-4;
    // Samples whose pdf or eval (max component) is below these are only checked for
    // finiteness and sign: their relative errors are dominated by float rounding.
    double min_pdf = 1e-4;
    double min_value = 1e-6;
};

struct ConsistencyResult
{
    std::uint64_t sample_count = 0;
    std::uint64_t checked_count = 0;  // non-delta samples with pdf/eval above the floors
    std::uint64_t weight_mismatch_count = 0;
    std::uint64_t pdf_mismatch_count = 0;
    std::uint64_t invalid_value_count = 0;  // non-finite or negative weight/pdf, bad direction,
                                            // pdf == 0 with a lobe type or pdf > 0 without one
    double max_weight_relative_error = 0.0;
    double max_pdf_relative_error = 0.0;
    std::string first_failure;  // description of the first failing sample
    bool ok() const { return weight_mismatch_count == 0 && pdf_mismatch_count == 0 && invalid_value_count == 0; }
};

ConsistencyResult check_sample_consistency(const SamplingTarget& target, const ConsistencyOptions& options);

// ------------------------------------------------------------------------------------------
// White furnace / directional albedo: mean of the sample weights (diffuse + specular, delta
// samples included, no-sample = 0), per channel, with its standard error.

struct AlbedoEstimate
{
    glm::dvec3 mean{0.0};
    glm::dvec3 standard_error{0.0};
    std::uint64_t sample_count = 0;
    glm::dvec3 max_weight{0.0};
};

// independent: standard error from the sample variance. low_discrepancy: `replicas`
// independently shifted R3 sequences, standard error from the spread of their means.
AlbedoEstimate estimate_albedo(const SamplingTarget& target, std::uint64_t sample_count, std::uint64_t seed,
                               SamplerKind sampler = SamplerKind::low_discrepancy, int replicas = 16);

// The independent estimate at growing sample counts, e.g. a furnace that draws 4x more while
// the standard error is too large. The samples are drawn in chunks, chunk c of a seed always
// the same numbers, and every count from 2^21 on has 256 chunks, so a larger count draws each
// chunk's numbers of the smaller one again first. This keeps each chunk's stream and sums where
// the last estimate stopped and draws only the rest: each estimate is estimate_albedo's at that
// count bit for bit (each chunk's sums added in the same order from the same state, merged in
// chunk order); counts with another chunk count start afresh.
class IndependentAlbedoSampler
{
  public:
    IndependentAlbedoSampler(const SamplingTarget& target, std::uint64_t seed);
    // sample_count: a multiple of the chunk count, e.g. a power of two >= 256.
    AlbedoEstimate estimate(std::uint64_t sample_count);

  private:
    const SamplingTarget& target_;
    std::uint64_t seed_;
    std::uint64_t per_chunk_ = 0;  // samples drawn so far in every chunk
    std::vector<RandomStream> streams_;
    std::vector<host::SampleWeightSums> sums_;
};

// ------------------------------------------------------------------------------------------
// Reciprocity of a single lobe.
//
// f(view, light) must return the lobe's value x |cos(light)| with the lobe initialized for
// `view` (local frame, z = normal), e.g. init + eval of the EON or microfacet lobe with weight
// 1. Reciprocity requires f(wo, wi) / |cos wi| == f(wi, wo) / |cos wo|.
//
// Only individual lobes are reciprocal. The full OpenPBR BSDF is deliberately not:
//  - albedo scaling weights the diffuse base by (1 - E_specular(wo)), a function of the view
//    alone (spec "non-reciprocal albedo scaling"), and the coat/fuzz layering does the same;
//  - Turquin multiple-scattering compensation scales each microfacet lobe by
//    1 + F0 (1 - E(mu_o)) / E(mu_o), again from the view alone;
//  - the lobe selection and compensation use the view's projected roughness for anisotropy;
//  - transmission between media of different IOR scales radiance by eta^2, so even an exact
//    BTDF satisfies f(wo, wi) / eta_i^2 = f(wi, wo) / eta_o^2 rather than plain symmetry.
// Hence reciprocity is tested per lobe with compensation disabled.
using LobeFunction = std::function<glm::vec3(const glm::vec3& view, const glm::vec3& light)>;

struct ReciprocityOptions
{
    double relative_tolerance = 1e-4;
    // Pairs where both orders are below this are skipped (relative errors of tiny values are
    // dominated by rounding).
    double min_value = 1e-6;
    // Float evaluation is also allowed the change that moving both directions by about this
    // many radians causes (measured per pair with 8 random moves; float directions carry about
    // 1e-7). This matters only where the lobe is ill-conditioned, e.g. the dielectric Fresnel
    // factor near the critical angle, whose slope is infinite: there rounding of 1e-7 in
    // 1 - sin^2(theta_t) can change 1 - F by 10% or more.
    double direction_precision = 1e-6;
    // Light over the full sphere (view above): transmission lobes get pairs on both sides.
    bool both_sides = false;
};

struct ReciprocityResult
{
    std::uint64_t pair_count = 0;
    std::uint64_t checked_count = 0;  // channel values where either order exceeds min_value
    std::uint64_t failure_count = 0;  // differences above relative_tolerance + conditioning
    double max_relative_error = 0.0;  // raw, for information
    double max_excess = 0.0;          // largest difference / allowed difference (<= 1 passes)
    std::string worst;                // the pair with the largest excess
};

// Random pairs: the view uniform over the upper hemisphere, the light over the upper
// hemisphere (or the sphere with both_sides).
ReciprocityResult check_reciprocity(const LobeFunction& f, std::uint64_t pair_count, std::uint64_t seed,
                                    const ReciprocityOptions& options = ReciprocityOptions());

// ------------------------------------------------------------------------------------------
// Small helpers for tests

// World direction with local cos theta `cos_theta` and azimuth `phi` in `basis`.
glm::vec3 direction_in_basis(const OpenPBR_Basis& basis, double cos_theta, double phi);
std::string describe_inputs(const OpenPBR_ResolvedInputs& inputs);
std::string to_string(const glm::vec3& v);

}  // namespace openpbr::testing

#endif
