// film_table_generator.h - generates table 5 of slang/openpbr_lut.h, the microfacet cosines at
// which a GGX reflection lobe reflects, which the thin film's lobe averages integrate over
// (openpbr_base_film_estimate, slang/lobes/openpbr_microfacet_reflection_lobe.h), and writes it
// as slang/generated/openpbr_film_lut_values.inc (the build appends its values to openpbr_lut.bin).
//
// What is tabulated. For the view wo = (sqrt(1 - mu^2), 0, mu) and isotropic GGX of roughness
// alpha, the light the lobe reflects comes from visible normals h ~ D_wo weighted by the
// reflected fraction G2(wo, wi) / G1(wo) (Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs"; 0 where wi = reflect(-wo, h) is below the horizon). The
// microfacet cosine c = wo.h of that light has a distribution on [0, 1] that depends on (mu, alpha)
// only. The table holds its quantile function and its partial first moment at the K
// probabilities p_k of openpbr_film_lobe_probability (slang/openpbr_lut.h: k / 32 for the even
// nodes, and 1/64 down to 1/512 from each end in the tails, where a narrow lobe's long GGX tails
// hold critical cosines):
//   channel 0  Q(p_k)                    the cosine below which a fraction p_k of the light lies
//   channel 1  M1(p_k) = E[c; c <= Q(p_k)]   (the mean restricted to that fraction, times p_k)
// A quantile axis puts nodes where the light is, whatever the width of the lobe: a near-mirror
// lobe's cosines span about alpha, a rough lobe's most of [0, 1]; on a cosine axis the first
// would fall inside one cell. Any threshold x (a critical cosine of the film stack) is found
// by inverting Q, and the light below it and its mean follow (openpbr_film_lobe_cumulative).
// Quantiles and first moments of neighbouring nodes blend like the lobes themselves (M1(p) is
// linear in Q); second moments would blend as a mixture, wider than either lobe, so there are
// none.
//
// Axes: p at the K nodes above; (node i of N at i / (N - 1)) c_mu = sqrt(mu), mu = max(c_mu^2,
// 1e-4); c_r = sqrt(alpha), alpha = max(c_r^2, 1e-4) (the other tables' view and roughness axes).
// Layout:
// index = ((channel * N + r_index) * N + mu_index) * K + p_index.
//
// Reference: a midpoint lattice of lattice_size^2 points through the spherical-cap sampler of
// visible normals (Dupuy and Benyoub 2023), each a point mass; the quantile at p_k splits the
// point it falls in. Deterministic (no random numbers).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace openpbr::host {

struct FilmTableOptions
{
    int size = 0;            // nodes on the view and roughness axes, e.g. 32 (0: the compiled size)
    int lattice_size = 256;  // reference points per axis per cell, e.g. 256 (65536 per cell)
    int threads = 0;         // 0: every core
};

// The microfacet cosines of one lobe, as the generator integrates them: (c, weight) pairs of the
// reference lattice, weight G2 / G1 (0 for a light below the horizon).
struct FilmLobePoint
{
    double cosine;
    double weight;
};
std::vector<FilmLobePoint> film_lobe_points(double mu, double alpha, int lattice_size);

// The probabilities of the compiled table's OPENPBR_LUT_FILM_QUANTILE_SIZE nodes, increasing from 0
// to 1 (openpbr_film_lobe_probability: the even nodes and the tail nodes).
std::vector<double> film_lobe_probabilities();

// Q and M1 at the given increasing probabilities (the first 0, the last 1) from the points (any
// order), in the channel order above: probabilities.size() values per channel.
std::vector<double> film_lobe_quantiles(std::vector<FilmLobePoint> points, const std::vector<double>& probabilities);

// The whole table in the layout above. Throws std::invalid_argument for sizes below 2.
std::vector<float> generate_film_table(const FilmTableOptions& options);

// "openpbr lutgen --only film: film lobe cosines 41 x 32 x 32 x 2, lattice 256^2" style comment.
std::string describe(const FilmTableOptions& options);

}  // namespace openpbr::host
