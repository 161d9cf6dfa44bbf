// Tests for slang/math/openpbr_thin_film.h (thin-film iridescence after Belcour & Barla 2017).
// The reference is computed here independently, in double precision: the textbook Airy
// reflectance of the three-media stack with complex Fresnel coefficients, sampled every 1 nm
// from 380 to 780 nm and integrated against the CIE 1931 colour matching functions (the
// multi-lobe analytic fit of Wyman, Sloan & Shirley 2013, JCGT 2(2)), then converted to the
// working space's linear RGB (slang/openpbr_working_space.h: Rec.709 with D65, or ACES AP1 with
// the ACES white) with a matrix built here from the primaries and the white, each channel
// normalized so a flat spectrum of 1 gives 1. The same tests run in each working space
// (test_thin_film and test_bsdf_lin_rec709, tests/bsdf/CMakeLists.txt).
#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "slang/math/openpbr_thin_film.h"
#include "slang/math/openpbr_fresnel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {

using Complex = std::complex<double>;
using Rgb = std::array<double, 3>;

constexpr double pi = 3.14159265358979323846;

// ---- Colour: CMFs, XYZ -> RGB, sensitivities ---------------------------------------------------

double piecewise_gaussian(double lambda, double mean, double sigma_below, double sigma_above)
{
    const double t = (lambda - mean) / (lambda < mean ? sigma_below : sigma_above);
    return std::exp(-0.5 * t * t);
}

// Wyman, Sloan & Shirley 2013, multi-lobe fit of the CIE 1931 2-degree observer (lambda in nm).
Rgb cie_xyz(double lambda)
{
    return {1.056 * piecewise_gaussian(lambda, 599.8, 37.9, 31.0) + 0.362 * piecewise_gaussian(lambda, 442.0, 16.0, 26.7) -
                0.065 * piecewise_gaussian(lambda, 501.1, 20.4, 26.2),
            0.821 * piecewise_gaussian(lambda, 568.8, 46.9, 40.5) + 0.286 * piecewise_gaussian(lambda, 530.9, 16.3, 31.1),
            1.217 * piecewise_gaussian(lambda, 437.0, 11.8, 36.0) + 0.681 * piecewise_gaussian(lambda, 459.0, 26.0, 13.8)};
}

using Matrix3 = std::array<std::array<double, 3>, 3>;

Matrix3 inverse(const Matrix3& m)
{
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Matrix3 r{};
    r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    return r;
}

// XYZ -> linear RGB of the working space from its primaries and white point (chromaticities):
// Rec.709 and D65 (ITU-R BT.709), or ACES AP1 and the ACES white (ACEScg, S-2014-004).
Matrix3 xyz_to_working_space()
{
#if OPENPBR_WORKING_SPACE == OPENPBR_WORKING_SPACE_ACESCG
    const double primaries[3][2] = {{0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044}};
    const double white[2] = {0.32168, 0.33767};
#else
    const double primaries[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    const double white[2] = {0.3127, 0.3290};
#endif
    Matrix3 p{};  // columns: XYZ of each primary with Y = 1
    for (int c = 0; c < 3; ++c)
    {
        const double x = primaries[c][0], y = primaries[c][1];
        p[0][c] = x / y;
        p[1][c] = 1.0;
        p[2][c] = (1.0 - x - y) / y;
    }
    const Matrix3 p_inverse = inverse(p);
    const double white_xyz[3] = {white[0] / white[1], 1.0, (1.0 - white[0] - white[1]) / white[1]};
    double scale[3];
    for (int c = 0; c < 3; ++c)
    {
        scale[c] = p_inverse[c][0] * white_xyz[0] + p_inverse[c][1] * white_xyz[1] + p_inverse[c][2] * white_xyz[2];
    }
    Matrix3 rgb_to_xyz{};
    for (int r = 0; r < 3; ++r)
    {
        for (int c = 0; c < 3; ++c)
        {
            rgb_to_xyz[r][c] = p[r][c] * scale[c];
        }
    }
    return inverse(rgb_to_xyz);
}

struct Sensitivities
{
    std::vector<double> wavelengths_nm;
    std::vector<Rgb> weights;  // per sample; each channel sums to 1
};

const Sensitivities& sensitivities()
{
    static const Sensitivities table = [] {
        Sensitivities s;
        const Matrix3 m = xyz_to_working_space();
        Rgb total{0.0, 0.0, 0.0};
        for (int lambda = 380; lambda <= 780; ++lambda)
        {
            const Rgb xyz = cie_xyz(lambda);
            const double trapezoid = (lambda == 380 || lambda == 780) ? 0.5 : 1.0;
            Rgb w{};
            for (int c = 0; c < 3; ++c)
            {
                w[c] = trapezoid * (m[c][0] * xyz[0] + m[c][1] * xyz[1] + m[c][2] * xyz[2]);
                total[c] += w[c];
            }
            s.wavelengths_nm.push_back(lambda);
            s.weights.push_back(w);
        }
        for (Rgb& w : s.weights)
        {
            for (int c = 0; c < 3; ++c)
            {
                w[c] /= total[c];
            }
        }
        return s;
    }();
    return table;
}

// ---- Optics in double precision ----------------------------------------------------------------

// Textbook Airy reflectance of outside (n_o) / film (n_f, d) / base (N = n + i k), averaged over
// s and p. Fields ~ e^{i(kz - wt)}: an absorbing index has k > 0, and cosines in the film and
// base are principal square roots (evanescent and absorbed waves decay).
double airy_reflectance(double lambda_nm, double cos_o, double n_o, double n_f, Complex n_base, double thickness_um)
{
    const double invariant_squared = n_o * n_o * (1.0 - cos_o * cos_o);
    const Complex cos_f = std::sqrt(Complex(1.0 - invariant_squared / (n_f * n_f), 0.0));
    const Complex n_cos_b = std::sqrt(n_base * n_base - invariant_squared);
    const Complex cos_b = n_cos_b / n_base;
    const Complex r12_s = (n_o * cos_o - n_f * cos_f) / (n_o * cos_o + n_f * cos_f);
    const Complex r23_s = (n_f * cos_f - n_cos_b) / (n_f * cos_f + n_cos_b);
    const Complex r12_p = (n_f * cos_o - n_o * cos_f) / (n_f * cos_o + n_o * cos_f);
    const Complex r23_p = (n_base * cos_f - n_f * cos_b) / (n_base * cos_f + n_f * cos_b);
    const Complex delta = 4.0 * pi * n_f * cos_f * (thickness_um * 1000.0) / lambda_nm;
    const Complex e = std::exp(Complex(0.0, 1.0) * delta);
    const Complex r_s = (r12_s + r23_s * e) / (1.0 + r12_s * r23_s * e);
    const Complex r_p = (r12_p + r23_p * e) / (1.0 + r12_p * r23_p * e);
    return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

// Bare interface outside / base (the zero-thickness limit).
double interface_reflectance(double cos_o, double n_o, Complex n_base)
{
    const double invariant_squared = n_o * n_o * (1.0 - cos_o * cos_o);
    const Complex n_cos_b = std::sqrt(n_base * n_base - invariant_squared);
    const Complex cos_b = n_cos_b / n_base;
    const Complex r_s = (n_o * cos_o - n_cos_b) / (n_o * cos_o + n_cos_b);
    const Complex r_p = (n_base * cos_o - n_o * cos_b) / (n_base * cos_o + n_o * cos_b);
    return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

// Incoherent (fringe-averaged) reflectance of the stack: R12 + T12^2 R23 / (1 - R12 R23) per
// polarization, for a propagating film on a dielectric base.
double incoherent_reflectance(double cos_o, double n_o, double n_f, double n_b)
{
    const double invariant_squared = n_o * n_o * (1.0 - cos_o * cos_o);
    const double cos_f = std::sqrt(1.0 - invariant_squared / (n_f * n_f));
    const double cos_b = std::sqrt(1.0 - invariant_squared / (n_b * n_b));
    double total = 0.0;
    for (int polarization = 0; polarization < 2; ++polarization)
    {
        const double r12 = polarization == 0 ? (n_o * cos_o - n_f * cos_f) / (n_o * cos_o + n_f * cos_f)
                                             : (n_f * cos_o - n_o * cos_f) / (n_f * cos_o + n_o * cos_f);
        const double r23 = polarization == 0 ? (n_f * cos_f - n_b * cos_b) / (n_f * cos_f + n_b * cos_b)
                                             : (n_b * cos_f - n_f * cos_b) / (n_b * cos_f + n_f * cos_b);
        const double big_r12 = r12 * r12, big_r23 = r23 * r23;
        total += big_r12 + (1.0 - big_r12) * (1.0 - big_r12) * big_r23 / (1.0 - big_r12 * big_r23);
    }
    return 0.5 * total;
}

// Brute-force spectral reference. A conductor's channel c uses (n_c, k_c) at every wavelength,
// the same assumption the library makes.
Rgb reference_rgb(double cos_o, double n_o, double n_f, const std::array<Complex, 3>& n_base, double thickness_um)
{
    const Sensitivities& s = sensitivities();
    Rgb rgb{0.0, 0.0, 0.0};
    for (size_t i = 0; i < s.wavelengths_nm.size(); ++i)
    {
        const double lambda = s.wavelengths_nm[i];
        const double r0 = airy_reflectance(lambda, cos_o, n_o, n_f, n_base[0], thickness_um);
        const double r1 = n_base[1] == n_base[0] ? r0 : airy_reflectance(lambda, cos_o, n_o, n_f, n_base[1], thickness_um);
        const double r2 = n_base[2] == n_base[0] ? r0 : airy_reflectance(lambda, cos_o, n_o, n_f, n_base[2], thickness_um);
        rgb[0] += s.weights[i][0] * r0;
        rgb[1] += s.weights[i][1] * r1;
        rgb[2] += s.weights[i][2] * r2;
    }
    // The true colour of a reflectance in [0, 1] can leave the RGB cube slightly (negative
    // lobes of the sensitivities); the library clamps, so the reference does too.
    for (double& v : rgb)
    {
        v = std::min(1.0, std::max(0.0, v));
    }
    return rgb;
}

std::array<Complex, 3> dielectric_base(double n_b) { return {Complex(n_b), Complex(n_b), Complex(n_b)}; }

bool finite_unit_interval(const glm::vec3& v)
{
    for (int c = 0; c < 3; ++c)
    {
        if (!(v[c] >= 0.0f && v[c] <= 1.0f))
        {
            return false;
        }
    }
    return true;
}

// Cosine at which the wave in a medium of index n turns evanescent (n_o sin = n), or -1.
double critical_cosine(double n_o, double n) { return n < n_o ? std::sqrt(1.0 - (n / n_o) * (n / n_o)) : -1.0; }

const std::vector<double> ior_values = {1.0 / 3.0, 0.5, 0.75, 1.0, 1.2, 1.33, 1.5, 2.0, 2.5, 3.0};

// ---- Tests ------------------------------------------------------------------------------------------

TEST(ThinFilm, ZeroThicknessIsTheBaseFresnelDielectric)
{
    double max_vs_library = 0.0, max_vs_double = 0.0;
    for (int i = 0; i <= 1000; ++i)
    {
        const float cos_theta = static_cast<float>(i) / 1000.0f;
        for (double n_o : ior_values)
        {
            for (double n_f : ior_values)
            {
                for (double n_b : ior_values)
                {
                    const float fo = static_cast<float>(n_o), ff = static_cast<float>(n_f), fb = static_cast<float>(n_b);
                    // The base Fresnel has an infinite slope at its critical angle: float
                    // rounding alone moves it by ~1e-3 there, so that neighbourhood is skipped.
                    const double cos_critical = critical_cosine(fo, fb);
                    if (std::abs(cos_theta - cos_critical) < 2e-3)
                    {
                        continue;
                    }
                    const glm::vec3 full = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, fo, ff, fb, 0.0f);
                    const glm::vec3 fast = openpbr::openpbr_thin_film_fresnel_dielectric_fast(cos_theta, fo, ff, fb, 0.0f);
                    const double exact = cos_theta < cos_critical ? 1.0 : interface_reflectance(cos_theta, fo, Complex(fb));
                    const float library = openpbr::openpbr_fresnel_dielectric(cos_theta, fb / fo);
                    for (int c = 0; c < 3; ++c)
                    {
                        max_vs_double = std::max({max_vs_double, std::abs(full[c] - exact), std::abs(fast[c] - exact)});
                        // openpbr_fresnel_dielectric itself loses ~1e-4 to cancellation at
                        // grazing incidence when eta is close to 1, so it is compared from 0.01.
                        if (cos_theta >= 0.01f)
                        {
                            max_vs_library = std::max({max_vs_library, static_cast<double>(std::abs(full[c] - library)),
                                                       static_cast<double>(std::abs(fast[c] - library))});
                        }
                    }
                }
            }
        }
    }
    std::printf("[ info ] zero thickness, dielectric: max |film - openpbr_fresnel_dielectric| = %.2e, "
                "max |film - double-precision Fresnel| = %.2e\n",
                max_vs_library, max_vs_double);
    EXPECT_LE(max_vs_library, 1e-4);
    EXPECT_LE(max_vs_double, 1e-4);
}

TEST(ThinFilm, ZeroThicknessIsTheBaseFresnelConductor)
{
    const std::vector<glm::vec3> n_values = {glm::vec3(0.18f, 0.42f, 1.37f), glm::vec3(1.35f, 0.96f, 0.63f),
                                             glm::vec3(0.05f, 1.0f, 3.0f)};
    const std::vector<glm::vec3> k_values = {glm::vec3(3.42f, 2.35f, 1.77f), glm::vec3(7.5f, 6.4f, 5.3f),
                                             glm::vec3(0.0f, 0.5f, 4.0f)};
    double max_error = 0.0;
    for (size_t m = 0; m < n_values.size(); ++m)
    {
        for (int i = 0; i <= 1000; ++i)
        {
            const float cos_theta = static_cast<float>(i) / 1000.0f;
            for (double n_o : {1.0, 1.5, 3.0})
            {
                for (double n_f : {0.5, 1.33, 2.0})
                {
                    const float fo = static_cast<float>(n_o), ff = static_cast<float>(n_f);
                    const glm::vec3 full =
                        openpbr::openpbr_thin_film_fresnel_conductor(cos_theta, fo, ff, n_values[m], k_values[m], 0.0f);
                    const glm::vec3 fast =
                        openpbr::openpbr_thin_film_fresnel_conductor_fast(cos_theta, fo, ff, n_values[m], k_values[m], 0.0f);
                    for (int c = 0; c < 3; ++c)
                    {
                        // n = 0.05, k = 0 has a critical angle of its own; skip its neighbourhood.
                        if (k_values[m][c] == 0.0f && std::abs(cos_theta - critical_cosine(fo, n_values[m][c])) < 2e-3)
                        {
                            continue;
                        }
                        const double exact = interface_reflectance(cos_theta, fo, Complex(n_values[m][c], k_values[m][c]));
                        max_error = std::max({max_error, std::abs(full[c] - exact), std::abs(fast[c] - exact)});
                    }
                }
            }
        }
    }
    std::printf("[ info ] zero thickness, conductor: max |film - exact conductor Fresnel| = %.2e\n", max_error);
    EXPECT_LE(max_error, 1e-4);
}

TEST(ThinFilm, FiniteAndWithinUnitIntervalEverywhere)
{
    const float denormal = std::numeric_limits<float>::denorm_min();
    std::vector<float> cosines = {0.0f, denormal, 1e-38f, 1e-20f, 1e-6f, 1e-3f, 0.9999999f, 1.0f};
    for (int i = 1; i < 40; ++i)
    {
        cosines.push_back(static_cast<float>(i) / 40.0f);
    }
    std::vector<float> thicknesses = {0.0f, denormal, 1e-30f, 1e-7f,  1e-3f,   0.01f,   1.5f,
                                      2.0f, 5.0f,     10.0f,  100.0f, 1000.0f, 1999.9f, 2000.0f};
    for (int i = 1; i <= 20; ++i)
    {
        thicknesses.push_back(0.05f * static_cast<float>(i));
    }
    std::vector<float> iors;
    for (double v : ior_values)
    {
        iors.push_back(static_cast<float>(v));
    }
    size_t checked = 0;
    for (float cos_theta : cosines)
    {
        for (float d : thicknesses)
        {
            for (float n_o : iors)
            {
                for (float n_f : iors)
                {
                    for (float n_b : iors)
                    {
                        const glm::vec3 full = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, n_o, n_f, n_b, d);
                        const glm::vec3 fast =
                            openpbr::openpbr_thin_film_fresnel_dielectric_fast(cos_theta, n_o, n_f, n_b, d);
                        ASSERT_TRUE(finite_unit_interval(full))
                            << "full cos " << cos_theta << " d " << d << " " << n_o << "/" << n_f << "/" << n_b;
                        ASSERT_TRUE(finite_unit_interval(fast))
                            << "fast cos " << cos_theta << " d " << d << " " << n_o << "/" << n_f << "/" << n_b;
                        checked += 2;
                    }
                    for (float n : {0.05f, 0.2f, 1.0f, 2.5f})
                    {
                        for (float k : {0.0f, 0.5f, 3.0f, 8.0f})
                        {
                            const glm::vec3 base_n(n, 0.5f * n + 0.1f, 3.0f);
                            const glm::vec3 base_k(k, 1.0f, 0.0f);
                            const glm::vec3 full =
                                openpbr::openpbr_thin_film_fresnel_conductor(cos_theta, n_o, n_f, base_n, base_k, d);
                            const glm::vec3 fast =
                                openpbr::openpbr_thin_film_fresnel_conductor_fast(cos_theta, n_o, n_f, base_n, base_k, d);
                            ASSERT_TRUE(finite_unit_interval(full)) << "conductor cos " << cos_theta << " d " << d << " "
                                                                    << n_o << "/" << n_f << " n " << n << " k " << k;
                            ASSERT_TRUE(finite_unit_interval(fast)) << "conductor fast cos " << cos_theta << " d " << d
                                                                    << " " << n_o << "/" << n_f << " n " << n << " k " << k;
                            checked += 2;
                        }
                    }
                }
            }
        }
    }
    EXPECT_GT(checked, 1000000u);
}

TEST(ThinFilm, NonFiniteInputsGiveFiniteResults)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (float bad : {nan, inf, -inf, -1.0f, 0.0f, 1e30f})
    {
        EXPECT_TRUE(finite_unit_interval(openpbr::openpbr_thin_film_fresnel_dielectric(bad, 1.0f, 1.33f, 1.5f, 0.4f)));
        EXPECT_TRUE(finite_unit_interval(openpbr::openpbr_thin_film_fresnel_dielectric(0.5f, bad, 1.33f, 1.5f, 0.4f)));
        EXPECT_TRUE(finite_unit_interval(openpbr::openpbr_thin_film_fresnel_dielectric(0.5f, 1.0f, bad, 1.5f, 0.4f)));
        EXPECT_TRUE(finite_unit_interval(openpbr::openpbr_thin_film_fresnel_dielectric(0.5f, 1.0f, 1.33f, bad, 0.4f)));
        EXPECT_TRUE(finite_unit_interval(openpbr::openpbr_thin_film_fresnel_dielectric(0.5f, 1.0f, 1.33f, 1.5f, bad)));
        EXPECT_TRUE(finite_unit_interval(openpbr::openpbr_thin_film_fresnel_dielectric_fast(0.5f, bad, bad, bad, bad)));
        EXPECT_TRUE(finite_unit_interval(
            openpbr::openpbr_thin_film_fresnel_conductor(0.5f, 1.0f, 1.33f, glm::vec3(bad), glm::vec3(bad), 0.4f)));
        EXPECT_TRUE(finite_unit_interval(
            openpbr::openpbr_thin_film_fresnel_conductor_fast(bad, 1.0f, 1.33f, glm::vec3(0.2f), glm::vec3(bad), bad)));
    }
}

struct StackCase
{
    const char* name;
    double n_o;
    double n_f;
    std::array<Complex, 3> base;
    bool conductor;
};

const std::vector<StackCase>& stack_cases()
{
    static const std::vector<StackCase> cases = {
        {"soap bubble air/1.33/air", 1.0, 1.33, dielectric_base(1.0), false},
        {"air/1.33/glass 1.5", 1.0, 1.33, dielectric_base(1.5), false},
        {"air/2.0/glass 1.5", 1.0, 2.0, dielectric_base(1.5), false},
        {"air/1.8/1.2", 1.0, 1.8, dielectric_base(1.2), false},
        {"coat 1.6/1.3/1.5 (evanescent film at grazing)", 1.6, 1.3, dielectric_base(1.5), false},
        {"glass 1.5/air gap/glass 1.5 (tunnelling)", 1.5, 1.0, dielectric_base(1.5), false},
        {"air/1.5/gold", 1.0, 1.5, {Complex(0.18, 3.42), Complex(0.42, 2.35), Complex(1.37, 1.77)}, true},
        {"air/1.33/aluminium", 1.0, 1.33, {Complex(1.35, 7.5), Complex(0.96, 6.4), Complex(0.63, 5.3)}, true},
        {"coat 1.6/1.3/copper", 1.6, 1.3, {Complex(0.27, 3.41), Complex(0.68, 2.63), Complex(1.32, 2.29)}, true},
    };
    return cases;
}

glm::vec3 evaluate(const StackCase& s, float cos_theta, float d, bool fast)
{
    const float n_o = static_cast<float>(s.n_o), n_f = static_cast<float>(s.n_f);
    if (s.conductor)
    {
        const glm::vec3 n(s.base[0].real(), s.base[1].real(), s.base[2].real());
        const glm::vec3 k(s.base[0].imag(), s.base[1].imag(), s.base[2].imag());
        return fast ? openpbr::openpbr_thin_film_fresnel_conductor_fast(cos_theta, n_o, n_f, n, k, d)
                    : openpbr::openpbr_thin_film_fresnel_conductor(cos_theta, n_o, n_f, n, k, d);
    }
    const float n_b = static_cast<float>(s.base[0].real());
    return fast ? openpbr::openpbr_thin_film_fresnel_dielectric_fast(cos_theta, n_o, n_f, n_b, d)
                : openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, n_o, n_f, n_b, d);
}

struct ErrorStats
{
    double max_error = 0.0;
    double sum_error = 0.0;
    size_t count = 0;
    double worst_d = 0.0, worst_cos = 0.0;
};

// Compares against the spectral reference for thickness 0.1..1 um and cos 0.05..1.
ErrorStats compare_with_reference(const StackCase& s, bool fast, double cos_min)
{
    ErrorStats stats;
    for (int di = 0; di <= 18; ++di)
    {
        const double d = 0.1 + 0.05 * di;
        for (int ci = 0; ci <= 40; ++ci)
        {
            const double cos_theta = cos_min + (1.0 - cos_min) * ci / 40.0;
            const Rgb reference = reference_rgb(cos_theta, s.n_o, s.n_f, s.base, d);
            const glm::vec3 value = evaluate(s, static_cast<float>(cos_theta), static_cast<float>(d), fast);
            for (int c = 0; c < 3; ++c)
            {
                const double e = std::abs(value[c] - reference[c]);
                stats.sum_error += e;
                ++stats.count;
                if (e > stats.max_error)
                {
                    stats.max_error = e;
                    stats.worst_d = d;
                    stats.worst_cos = cos_theta;
                }
            }
        }
    }
    return stats;
}

TEST(ThinFilm, MatchesSpectralReference)
{
    for (const StackCase& s : stack_cases())
    {
        for (double cos_min : {0.2, 0.01})
        {
            const ErrorStats stats = compare_with_reference(s, false, cos_min);
            std::printf("[ info ] full, cos >= %.2f, %-46s max %.4f (d %.2f um, cos %.3f), mean %.5f\n", cos_min, s.name,
                        stats.max_error, stats.worst_d, stats.worst_cos, stats.sum_error / stats.count);
            EXPECT_LE(stats.max_error, cos_min >= 0.2 ? 0.01 : 0.02) << s.name;
            EXPECT_LE(stats.sum_error / stats.count, 0.002) << s.name;
        }
    }
}

// The fast model trades accuracy for speed; these loose bounds only catch regressions. Its
// measured error is printed for the accuracy / performance comparison.
TEST(ThinFilm, FastModelStaysCloseToReference)
{
    for (const StackCase& s : stack_cases())
    {
        const ErrorStats stats = compare_with_reference(s, true, 0.01);
        std::printf("[ info ] fast, cos >= 0.01, %-46s max %.4f (d %.2f um, cos %.3f), mean %.5f\n", s.name, stats.max_error,
                    stats.worst_d, stats.worst_cos, stats.sum_error / stats.count);
        EXPECT_LE(stats.max_error, 0.25) << s.name;
        EXPECT_LE(stats.sum_error / stats.count, 0.03) << s.name;
    }
}

TEST(ThinFilm, SoapBubbleIsIridescent)
{
    const glm::vec3 rgb = openpbr::openpbr_thin_film_fresnel_dielectric(1.0f, 1.0f, 1.33f, 1.0f, 0.3f);
    const Rgb reference = reference_rgb(1.0, 1.0, 1.33, dielectric_base(1.0), 0.3);
    std::printf("[ info ] soap film 0.3 um at normal incidence: RGB %.4f %.4f %.4f (reference %.4f %.4f %.4f)\n", rgb.x,
                rgb.y, rgb.z, reference[0], reference[1], reference[2]);
    const float spread = std::max({rgb.x, rgb.y, rgb.z}) - std::min({rgb.x, rgb.y, rgb.z});
    // The uncoated interface reflects 2 % (flat); the film must colour it clearly.
    EXPECT_GT(spread, 0.03f);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(rgb[c], reference[c], 0.01);
    }
}

TEST(ThinFilm, ThickFilmAveragesTheFringesOut)
{
    // Hundreds of fringes fall inside each colour channel: the spectral integration must give
    // the incoherent reflectance, identical in every channel, not an aliased colour.
    for (float d : {50.0f, 300.0f, 2000.0f})
    {
        for (float cos_theta : {1.0f, 0.7f, 0.3f, 0.1f})
        {
            const double incoherent = incoherent_reflectance(cos_theta, 1.0, 1.33, 1.5);
            const glm::vec3 full = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, 1.0f, 1.33f, 1.5f, d);
            const glm::vec3 fast = openpbr::openpbr_thin_film_fresnel_dielectric_fast(cos_theta, 1.0f, 1.33f, 1.5f, d);
            for (int c = 0; c < 3; ++c)
            {
                EXPECT_NEAR(full[c], incoherent, 2e-3) << "d " << d << " cos " << cos_theta;
                EXPECT_NEAR(fast[c], incoherent, 2e-3) << "d " << d << " cos " << cos_theta;
            }
        }
    }
}

TEST(ThinFilm, IndexMatchedFilmIsInvisible)
{
    for (float d : {0.05f, 0.3f, 1.0f, 10.0f})
    {
        for (float cos_theta : {1.0f, 0.5f, 0.1f})
        {
            // Film index equal to the outside: only the film/base interface reflects.
            const glm::vec3 matched_outside = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, 1.5f, 1.5f, 1.2f, d);
            const float base = openpbr::openpbr_fresnel_dielectric(cos_theta, 1.2f / 1.5f);
            // Film index equal to the base: only the outside/film interface reflects.
            const glm::vec3 matched_base = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, 1.0f, 1.5f, 1.5f, d);
            const float top = openpbr::openpbr_fresnel_dielectric(cos_theta, 1.5f);
            for (int c = 0; c < 3; ++c)
            {
                EXPECT_NEAR(matched_outside[c], base, 1e-4);
                EXPECT_NEAR(matched_base[c], top, 1e-4);
            }
        }
    }
}

TEST(ThinFilm, TotalInternalReflection)
{
    // Base TIR: everything reflects, whatever the film.
    for (float d : {0.0f, 0.2f, 5.0f})
    {
        const glm::vec3 rgb = openpbr::openpbr_thin_film_fresnel_dielectric(0.2f, 1.5f, 1.33f, 1.0f, d);
        EXPECT_EQ(rgb, glm::vec3(1.0f));
    }
    // A low-index gap between two glasses beyond its critical angle: a thin gap lets light
    // tunnel through (frustrated TIR), a thick one reflects all of it.
    const float cos_theta = 0.3f;  // sin 0.954: 1.5 sin = 1.43 > 1
    const glm::vec3 closed = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, 1.5f, 1.0f, 1.5f, 0.0f);
    const glm::vec3 thin = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, 1.5f, 1.0f, 1.5f, 0.05f);
    const glm::vec3 thick = openpbr::openpbr_thin_film_fresnel_dielectric(cos_theta, 1.5f, 1.0f, 1.5f, 5.0f);
    const Rgb thin_reference = reference_rgb(cos_theta, 1.5, 1.0, dielectric_base(1.5), 0.05);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(closed[c], 0.0f, 1e-6f);
        EXPECT_GT(thin[c], 0.05f);
        EXPECT_LT(thin[c], 0.95f);
        EXPECT_NEAR(thin[c], thin_reference[c], 0.01);
        EXPECT_NEAR(thick[c], 1.0f, 1e-4f);
    }
    // Thin tunnelling gaps transmit more red than blue (longer evanescent decay length).
    EXPECT_LT(thin.x, thin.z);
}

TEST(ThinFilm, ContinuousAcrossTheFilmCriticalAngle)
{
    // Coat 1.6 over a 1.3 film: the film turns evanescent at cos = sqrt(1 - (1.3/1.6)^2); the
    // model switches there from the Fourier series to the exact evaluation.
    const float cos_critical = static_cast<float>(critical_cosine(1.6, 1.3));
    for (float d : {0.05f, 0.3f, 1.0f})
    {
        const glm::vec3 below = openpbr::openpbr_thin_film_fresnel_dielectric(cos_critical - 1e-4f, 1.6f, 1.3f, 1.5f, d);
        const glm::vec3 above = openpbr::openpbr_thin_film_fresnel_dielectric(cos_critical + 1e-4f, 1.6f, 1.3f, 1.5f, d);
        const glm::vec3 metal_below = openpbr::openpbr_thin_film_fresnel_conductor(
            cos_critical - 1e-4f, 1.6f, 1.3f, glm::vec3(0.27f, 0.68f, 1.32f), glm::vec3(3.41f, 2.63f, 2.29f), d);
        const glm::vec3 metal_above = openpbr::openpbr_thin_film_fresnel_conductor(
            cos_critical + 1e-4f, 1.6f, 1.3f, glm::vec3(0.27f, 0.68f, 1.32f), glm::vec3(3.41f, 2.63f, 2.29f), d);
        for (int c = 0; c < 3; ++c)
        {
            EXPECT_NEAR(below[c], above[c], 0.01) << "d " << d;
            EXPECT_NEAR(metal_below[c], metal_above[c], 0.01) << "d " << d;
        }
    }
}

TEST(ThinFilm, GulbrandsenReproducesNormalIncidenceReflectivity)
{
    const glm::vec3 r(0.95f, 0.64f, 0.54f);  // gold-like F0
    for (const glm::vec3& g : {glm::vec3(0.0f), glm::vec3(0.5f), glm::vec3(1.0f), glm::vec3(0.9f, 0.6f, 0.3f)})
    {
        const glm::vec3 n = openpbr::openpbr_gulbrandsen_n(r, g);
        const glm::vec3 k = openpbr::openpbr_gulbrandsen_k(r, n);
        const glm::vec3 film_free = openpbr::openpbr_thin_film_fresnel_conductor(1.0f, 1.0f, 1.5f, n, k, 0.0f);
        for (int c = 0; c < 3; ++c)
        {
            const double f0 = interface_reflectance(1.0, 1.0, Complex(n[c], k[c]));
            EXPECT_NEAR(f0, r[c], 1e-4) << "g " << g[c];
            EXPECT_NEAR(film_free[c], r[c], 1e-4) << "g " << g[c];
            // g = 0: the dielectric (k = 0) end, n = (1 + sqrt r) / (1 - sqrt r);
            // g = 1: n = (1 - r) / (1 + r).
            if (g[c] == 0.0f)
            {
                EXPECT_NEAR(k[c], 0.0f, 2e-2f * n[c]);
            }
            if (g[c] == 1.0f)
            {
                EXPECT_NEAR(n[c], (1.0f - r[c]) / (1.0f + r[c]), 1e-5f);
            }
        }
    }
    // Black and unit reflectivity stay finite.
    const glm::vec3 n_edge = openpbr::openpbr_gulbrandsen_n(glm::vec3(0.0f, 1.0f, 0.5f), glm::vec3(0.5f));
    const glm::vec3 k_edge = openpbr::openpbr_gulbrandsen_k(glm::vec3(0.0f, 1.0f, 0.5f), n_edge);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_TRUE(std::isfinite(n_edge[c]) && std::isfinite(k_edge[c]));
    }
}

}  // namespace
