// Thin-film iridescence Fresnel (OpenPBR 1.1 "Thin-film iridescence", docs/spec-notes.md §7),
// after Belcour & Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of
// Varying Iridescence" (ACM TOG 36(4), SIGGRAPH 2017).
//
// Three media, each described by its absolute index of refraction: the outside (ambient or
// coat, n_o), a non-absorbing film (n_f, thickness d) and the base, either a dielectric (real
// n_b) or a conductor (complex N = n + i k per RGB channel). cos_theta is the cosine between the
// incident direction and the microfacet normal, on the outside. All functions return the
// reflectance of the whole stack averaged over the s and p polarizations, per RGB channel, in
// [0, 1]. Linear RGB is the working space (slang/openpbr_working_space.h), and a spectrally
// flat reflectance R maps to RGB (R, R, R) (see "Spectral lobes" below), so a zero-thickness
// film gives exactly the plain Fresnel factor of the base. The film does not absorb, so for a
// dielectric base the transmittance of the stack is 1 minus the returned reflectance.
//
// Phase convention: the fields vary as e^{i(k z - w t)}, so an absorbing medium has index
// n + i k with k >= 0 and a round trip through the film multiplies the amplitude by
// e^{i delta}, delta = 4 pi n_f d cos_f / lambda.
//
// Full model (openpbr_thin_film_fresnel_dielectric / _conductor):
//  * Airy summation. With r_ij, t_ij the amplitude coefficients of one polarization
//    (r_ji = -r_ij, t_12 t_21 = 1 - r_12^2 = T12 for the dielectric outside/film interface),
//    the film reflects r = r12 + t12 t21 r23 e^{i delta} sum_k (r21 r23 e^{i delta})^k. Writing
//    z = r21 r23 e^{i delta} (|z| = sqrt(R12 R23)), |r|^2 is a Fourier series in the phase:
//        R(delta) = C0 + 2 A sum_{m>=1} Re(z^m),
//        C0 = R12 + T12^2 R23 / (1 - R12 R23)   (the incoherent, phase-averaged reflectance)
//        A  = T12^2 R23 / (1 - R12 R23) - T12 = -T12 T23 / (T12 + R12 T23),   T23 = 1 - R23,
//    the same Fourier series in the film phase as Belcour & Barla's C_0, C_m (derived here
//    with the phase shifts of r21 and r23 kept inside z, and A in a form that does not cancel
//    when R12 -> 1). A conductor base enters through its complex r23.
//  * Spectral integration. Each RGB sensitivity, written as a density over the wavenumber
//    nu = 1/lambda, is a sum of Gaussian lobes. Since delta = 2 pi OPD nu (OPD = 2 n_f d cos_f)
//    is linear in nu, the average of Re(z^m) over a Gaussian lobe (centre nu_j, deviation
//    sigma_j) is Re(z_j^m) g_j^(m^2), with z_j evaluated at nu_j and
//    g_j = exp(-(2 pi OPD sigma_j)^2 / 2): the Fourier transform of the Gaussian, the paper's
//    closed form. Fringes finer than the sensitivities are damped out instead of aliased, so a
//    thick film tends to the incoherent C0.
//  * Harmonics first, lobes inside them. The RGB weights are linear, so the sum over lobes
//    commutes with the sum over harmonics: channel c reflects
//        R_c = C0 + 2 A sum_m Re(rho^m H_c(m)),   H_c(m) = sum_j W_cj g_j^(m^2) e^{i m delta_j},
//    (rho = r21 r23, z = rho e^{i delta}; the weights W_cj sum to 1). H depends only on the film
//    and the angle, not on the base or the polarization, so one set of film harmonics serves
//    both polarizations, the three channels of a conductor, and the dielectric and metal bases
//    evaluated at the same microfacet angle (openpbr_thin_film_harmonic_sum). The series keeps
//    M = 4 harmonics explicitly and sums the rest in closed form as a geometric series: for
//    m > M, g^(m^2) becomes g^((M+1)^2 + 3 (M+1)(m - M - 1)), the chord of the exponent between
//    m = M+1 and m = 2(M+1). The tail is exact for g = 1, so a zero-thickness film reproduces
//    the base Fresnel exactly and near grazing angles, where |z| -> 1 and the Airy peaks become
//    sharp, there is no truncation ringing. The chord (rather than the tangent at m = M+1) was
//    chosen by the error against the spectral reference: it halves the worst grazing-angle
//    error. The tail needs one complex division per lobe and polarization, so it is evaluated
//    only where it can matter (OPENPBR_THIN_FILM_TRUNCATION_ERROR); the four-lane form below also
//    leaves out explicit harmonics whose bound is below a fifth of that setting.
//  * Two forms of one evaluation, chosen per language by OPENPBR_FILM_FOUR_LANES
//    (interop/openpbr_interop.h; the same reflectance within 1e-5). One lane (0, the GPU
//    languages and C++ without SIMD): the stacks one after another, the film's harmonics summed
//    once per evaluation (openpbr_thin_film_harmonics). Four lanes (1, C++ with GLM's SIMD):
//    the four stacks that differ in their base (the conductor's three channels and
//    the dielectric) are evaluated side by side in the lanes of vec4s, and the six lobes' phases
//    (sine, cosine and damping, computed once) in two more: the harmonics, every stack's series
//    and the closed-form tail read them (openpbr_thin_film_fresnel_bases). A dielectric base is
//    a conductor channel whose imaginary parts are 0, so one lane's arithmetic serves all four.
//  * Evanescent film: when n_o sin(theta) >= n_f the wave does not propagate in the film
//    (frustrated total internal reflection) and there is no fringe; the reflectance is then
//    smooth in wavelength and is evaluated exactly at each lobe centre with the film's
//    characteristic-matrix form (below), which is continuous with the propagating case.
//  * Dispersion is ignored: n_o, n_f and n_b do not vary across the spectrum. A conductor's
//    channel c uses (n_c, k_c) over the whole spectrum, i.e. each channel is the film on a
//    spectrally constant metal (the usual RGB-renderer approximation).
//
// Fast model (..._fast): one Gaussian per channel (a single-Gaussian fit of that channel's
// sensitivity) instead of six shared lobes, and harmonic m damped by g^m instead of g^(m^2),
// which sums in closed form: R = C0 + 2 A Re(g z / (1 - g z)) per polarization, the Airy
// formula with the round trip attenuated by g. Exact for a zero-thickness film and in the
// thick-film limit (no aliasing); in between a single positive Gaussian cannot follow the
// negative lobes of the RGB sensitivities, so the colour of a 0.3-1 um film can be off by up
// to ~0.2 near grazing (mean error 0.004-0.02).
//
// Measured against a brute-force spectral reference (1 nm steps, tests/bsdf/test_thin_film.cpp),
// films 0.1-1 um: full model max error 0.002 (dielectric base, cos >= 0.2), 0.004 (metals),
// 0.008 down to cos = 0.01; zero thickness matches the base Fresnel within 1e-5.
#ifndef OPENPBR_THIN_FILM_H
#define OPENPBR_THIN_FILM_H

#include "openpbr_math.h"

// Largest reflectance the closed-form tail may drop, e.g. 1e-5. Harmonic m is at most
// 2 |A| g^(m^2) |rho|^m in size, so the harmonics after the fourth sum to at most
// 2 |A| g^25 |rho|^5 / (1 - |rho|); the tail (a complex division per lobe and polarization) is
// evaluated only where that bound, with the largest lobe damping g, is above this value.
// |rho| = |r21 r23| is small away from grazing incidence (0.006 for a 1.4 film on 1.5 glass,
// about 0.15 on a metal), so most evaluations skip it. The explicit harmonics m = 1..4 are
// summed only as far as the later ones could add a fifth of this value to a channel (with the
// largest channel's sum of absolute lobe weights, 2.49). 1e-5 is a thirtieth of the smallest
// error of the full model against the spectral reference (0.0003-0.008, tests/bsdf/test_thin_film.cpp).
#ifndef OPENPBR_THIN_FILM_TRUNCATION_ERROR
#define OPENPBR_THIN_FILM_TRUNCATION_ERROR 1e-5f
#endif

// Inputs are clamped into these ranges (NaN goes to the lower bound), so every input gives a
// finite result. Thicker films are indistinguishable from the incoherent limit.
#define OPENPBR_THIN_FILM_MIN_IOR 0.01f
#define OPENPBR_THIN_FILM_MAX_IOR 100.0f
#define OPENPBR_THIN_FILM_MAX_EXTINCTION 1000.0f
#define OPENPBR_THIN_FILM_MAX_THICKNESS_UM 100000.0f

// Spectral lobes. Each RGB sensitivity of the working space (slang/openpbr_working_space.h),
// as a density over the wavenumber nu in um^-1, is a sum of six Gaussian lobes shared by every
// space:
//   s_c(nu) = sum_j W_cj N(nu; nu_j, sigma_j^2),   sum_j W_cj = 1,
// where s_c = (M XYZ-CMF)_c / integral, with the CIE 1931 2-degree colour matching functions
// from the multi-lobe analytic fit of Wyman, Sloan & Shirley 2013, "Simple Analytic
// Approximations to the CIE XYZ Color Matching Functions" (JCGT 2(2)), restricted to
// 380..780 nm, and M the XYZ -> linear RGB matrix of the working space's primaries and white
// point. Each channel is normalized so that a spectrally flat reflectance 1 gives 1
// (equal-energy white maps to RGB (1, 1, 1)). The lobes (nu_j, sigma_j) were fit once with the
// Rec.709 weights; the sensitivities of another RGB space are a linear transform of those, so
// the same lobes serve it, with weights refit per space (least squares over wavenumbers
// 1/0.78 .. 1/0.38 um^-1, the weights constrained to sum to 1 per channel, a 1e-4 ridge term
// against cancelling lobe pairs). L1 error of the fit: 0.025, 0.012, 0.015 (R, G, B) of the
// unit-area Rec.709 sensitivities, 0.017, 0.010, 0.013 for ACEScg. Belcour & Barla fit
// Gaussians to the XYZ functions and convert afterwards; fitting the RGB sensitivities directly
// puts the fit error where it is seen, and makes every channel's weights sum to 1 so a flat
// reflectance stays exactly flat. The fast model's one Gaussian per channel is a least-squares
// fit of the same sensitivities (amplitude free; the model uses it at unit area).
// OPENPBR_THIN_FILM_LOBE<j>_NU, _SIGMA, _WEIGHT and OPENPBR_THIN_FILM_FAST_NU, _SIGMA are
// generated for each working space by tools/make_colour_tables.py into
// slang/generated/openpbr_working_space_constants.h (included through openpbr_math.h).

OPENPBR_NAMESPACE_BEGIN

// ---- Complex numbers as vec2 (x = real part, y = imaginary part) ----------------------------

OPENPBR_FUNC vec2 openpbr_complex_multiply(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

OPENPBR_FUNC float openpbr_complex_norm_squared(vec2 a) { return a.x * a.x + a.y * a.y; }

// a / b; a vanishing b is replaced by a tiny one so the result stays finite (callers multiply
// such quotients by a factor that vanishes with b).
OPENPBR_FUNC vec2 openpbr_complex_divide(vec2 a, vec2 b)
{
    const float inverse_norm = 1.0f / max(openpbr_complex_norm_squared(b), 1e-30f);
    return vec2(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) * inverse_norm;
}

// Principal square root (real part >= 0; imaginary part has the sign of a.y, here always >= 0
// so waves decay into absorbing media). Each branch avoids subtracting nearly equal numbers.
OPENPBR_FUNC vec2 openpbr_complex_sqrt(vec2 a)
{
    const float magnitude = sqrt(openpbr_complex_norm_squared(a));
    if (a.x >= 0.0f)
    {
        const float real_part = sqrt(0.5f * (magnitude + a.x));
        return vec2(real_part, real_part > 0.0f ? 0.5f * a.y / real_part : 0.0f);
    }
    const float imaginary_magnitude = sqrt(0.5f * (magnitude - a.x));
    const float imaginary_part = a.y >= 0.0f ? imaginary_magnitude : -imaginary_magnitude;
    return vec2(0.5f * abs(a.y) / imaginary_magnitude, imaginary_part);
}

// ---- Inputs ---------------------------------------------------------------------------------------

// (n cos)^2 in a medium of real index n for a wave arriving from index n_o:
// n^2 - n_o^2 sin^2 = (n - n_o)(n + n_o) + (n_o cos_o)^2. This form keeps its precision when
// n is close to n_o at grazing incidence, where n^2 - n_o^2 sin^2 would cancel.
OPENPBR_FUNC float openpbr_thin_film_normal_term(float n, float n_o, float outside_normal_term)
{
    return (n - n_o) * (n + n_o) + outside_normal_term;
}

struct OpenPBR_ThinFilmInputs OPENPBR_DIFFERENTIABLE
{
    float cos_o;
    float n_o;
    float n_f;
    float thickness_um;
    float outside_normal_term;  // (n_o cos theta)^2
    float film_normal_term;     // (n_f cos_f)^2 = n_f^2 - (n_o sin theta)^2, n_o sin theta being
                                // conserved across parallel interfaces (Snell)
    // Standard deviation of the film's optical path difference over the microfacets a caller
    // averages at once (openpbr_base_film_estimate), e.g. 0.02 um; 0 for one microfacet. The
    // fringes then average out as they do over a spectral lobe: harmonic m of spectral lobe j
    // is damped by exp(-(2 pi m)^2 (OPD^2 sigma_j^2 + nu_j^2 spread^2) / 2), the Gaussian
    // phase average of Belcour & Barla 2017 with the path as a second Gaussian variable.
    float optical_path_spread_um;
};

OPENPBR_FUNC OpenPBR_ThinFilmInputs openpbr_thin_film_inputs(float cos_theta, float eta_outside, float eta_film,
                                                             float thickness_um)
{
    OpenPBR_ThinFilmInputs inputs;
    inputs.cos_o = openpbr_clamp_finite(cos_theta, 0.0f, 1.0f);
    inputs.n_o = openpbr_clamp_finite(eta_outside, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    inputs.n_f = openpbr_clamp_finite(eta_film, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    inputs.thickness_um = openpbr_clamp_finite(thickness_um, 0.0f, OPENPBR_THIN_FILM_MAX_THICKNESS_UM);
    inputs.outside_normal_term = openpbr_square(inputs.n_o * inputs.cos_o);
    inputs.film_normal_term = openpbr_thin_film_normal_term(inputs.n_f, inputs.n_o, inputs.outside_normal_term);
    inputs.optical_path_spread_um = 0.0f;
    return inputs;
}

// spread_phase_variance: (2 pi s)^2 for a path spread s (OpenPBR_ThinFilmInputs), the phase
// variance per unit nu^2 it adds; 0 for one microfacet.
OPENPBR_FUNC float openpbr_thin_film_spread_phase_variance(float optical_path_spread_um)
{
    return openpbr_square(OPENPBR_TWO_PI * optical_path_spread_um);
}

// ---- The stack at one channel ------------------------------------------------------------------

// One polarization's Airy series R(delta) = mean + 2 amplitude sum_{m>=1} Re(z^m), z = rho e^{i delta}.
struct OpenPBR_ThinFilmPolarization OPENPBR_DIFFERENTIABLE
{
    float mean;          // C0: the incoherent reflectance (average over the film phase)
    float amplitude;     // A = -T12 T23 / (T12 + R12 T23)
    vec2 rho;            // r21 r23: one internal round trip without the propagation phase
    vec2 one_minus_rho;  // 1 - rho, from a form without cancellation (it vanishes near grazing)
    float tail_bound;    // 2 |A| |rho|^5 / (1 - |rho|): bounds the harmonics m >= 5 (before damping)
};

// Everything about the film and base that does not depend on wavelength, for one channel.
struct OpenPBR_ThinFilmStack OPENPBR_DIFFERENTIABLE
{
    OpenPBR_ThinFilmPolarization s;
    OpenPBR_ThinFilmPolarization p;
    bool film_is_evanescent;  // n_o sin(theta) >= n_f: no propagating wave in the film
    float thickness_um;
    float optical_path_difference_um;  // 2 n_f d cos_f (0 when evanescent)
    float optical_path_spread_um;      // deviation of that path over the microfacets averaged (0: one)
    float film_normal_term;            // (n_f cos_f)^2 = n_f^2 - (n_o sin theta)^2, any sign
    float film_ior_squared;
    float outside_admittance_s;  // n_o cos_o
    float outside_admittance_p;  // cos_o / n_o
    vec2 base_admittance_s;      // N cos_b
    vec2 base_ior_squared;       // N^2 (the p admittance cos_b / N = N cos_b / N^2 is formed only
                                 // where the film is evanescent: one complex division saved per stack)
};

// Series data of one polarization from the two interfaces' Fresnel coefficients written as
// r12 = (a1 - b1) / (a1 + b1) (outside -> film, real, a1, b1 >= 0) and
// r23 = (a2 - b2) / (a2 + b2) (film -> base, complex for a conductor).
OPENPBR_FUNC OpenPBR_ThinFilmPolarization openpbr_thin_film_polarization(float a1, float b1, vec2 a2, vec2 b2)
{
    const float inverse_sum_1 = 1.0f / max(a1 + b1, 1e-30f);
    const float r12 = (a1 - b1) * inverse_sum_1;
    const float reflectance_12 = r12 * r12;
    // 1 - R12 computed directly: it vanishes at grazing incidence, where R12 rounds to 1.
    const float transmittance_12 = 4.0f * a1 * b1 * inverse_sum_1 * inverse_sum_1;
    // Quotients by a2 + b2 as multiplications by conj(a2 + b2) / |a2 + b2|^2 (one division).
    const vec2 conjugate_sum_2 = vec2(a2.x + b2.x, -(a2.y + b2.y));
    const float inverse_sum_2_norm = 1.0f / max(openpbr_complex_norm_squared(conjugate_sum_2), 1e-30f);
    const vec2 r23 = openpbr_complex_multiply(a2 - b2, conjugate_sum_2) * inverse_sum_2_norm;
    const float reflectance_23 = openpbr_complex_norm_squared(r23);
    // 1 - |r23|^2 = 4 Re(a2 conj(b2)) / |a2 + b2|^2: the power entering the base.
    const float transmittance_23 = max(4.0f * (a2.x * b2.x + a2.y * b2.y) * inverse_sum_2_norm, 0.0f);
    // 1 - R12 R23 = T12 + R12 T23 (using R12 + T12 = 1), again without cancellation.
    const float inverse_denominator = 1.0f / max(transmittance_12 + reflectance_12 * transmittance_23, 1e-30f);
    OpenPBR_ThinFilmPolarization polarization;
    polarization.mean = reflectance_12 + transmittance_12 * transmittance_12 * reflectance_23 * inverse_denominator;
    polarization.amplitude = -transmittance_12 * transmittance_23 * inverse_denominator;
    polarization.rho = -r12 * r23;
    // 1 + r12 r23 = 2 (a1 a2 + b1 b2) / ((a1 + b1)(a2 + b2)).
    polarization.one_minus_rho =
        openpbr_complex_multiply(2.0f * (a1 * a2 + b1 * b2), conjugate_sum_2) * (inverse_sum_2_norm * inverse_sum_1);
    // |rho|^2 = R12 R23 and 1 - |rho| = (1 - R12 R23) / (1 + |rho|), without cancellation.
    const float rho_squared = reflectance_12 * reflectance_23;
    const float rho_magnitude = sqrt(rho_squared);
    polarization.tail_bound = 2.0f * abs(polarization.amplitude) * rho_squared * rho_squared * rho_magnitude *
                              (1.0f + rho_magnitude) * inverse_denominator;
    return polarization;
}

// The stack for a base of squared complex index base_ior_squared (N^2) and
// base_normal_term = N cos_b = sqrt(N^2 - (n_o sin theta)^2) (principal root).
// Needs cos_o > 0. A dielectric base under total internal reflection is handled by the caller
// (the result is 1); a conductor's complex N cos_b never vanishes unless k = 0, and a k = 0
// base beyond its critical angle gives R23 = 1, T23 = 0 and so a total reflection here too.
OPENPBR_FUNC OpenPBR_ThinFilmStack openpbr_thin_film_stack(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs, vec2 base_ior_squared,
                                                           vec2 base_normal_term)
{
    const float cos_o = inputs.cos_o;
    const float n_o = inputs.n_o;
    const float n_f = inputs.n_f;
    const float film_normal_term = inputs.film_normal_term;
    OpenPBR_ThinFilmStack stack;
    stack.film_is_evanescent = film_normal_term <= 0.0f;
    const float cos_f = openpbr_safe_sqrt(film_normal_term) / n_f;
    stack.thickness_um = inputs.thickness_um;
    stack.optical_path_difference_um = 2.0f * n_f * cos_f * inputs.thickness_um;
    stack.optical_path_spread_um = inputs.optical_path_spread_um;
    stack.film_normal_term = film_normal_term;
    stack.film_ior_squared = n_f * n_f;
    stack.outside_admittance_s = n_o * cos_o;
    stack.outside_admittance_p = cos_o / n_o;
    stack.base_admittance_s = base_normal_term;
    stack.base_ior_squared = base_ior_squared;
    // s: r_ij = (n_i cos_i - n_j cos_j) / (n_i cos_i + n_j cos_j);
    // p: r_ij = (n_j cos_i - n_i cos_j) / (n_j cos_i + n_i cos_j), with the film -> base pair
    // multiplied through by N so that only N^2 and N cos_b appear.
    const float film_term = n_f * cos_f;
    stack.s = openpbr_thin_film_polarization(n_o * cos_o, film_term, vec2(film_term, 0.0f), base_normal_term);
    stack.p = openpbr_thin_film_polarization(n_f * cos_o, n_o * cos_f, base_ior_squared * cos_f, n_f * base_normal_term);
    return stack;
}

// ---- Exact reflectance at one wavenumber (evanescent film) ------------------------------------

// One polarization from the film's characteristic-matrix form: the Airy formula
// r = (r12 + r23 e^{2 i beta}) / (1 + r12 r23 e^{2 i beta}), beta = k0 d n_f cos_f, multiplied
// through by (Y_o + Y_f)(Y_f + Y_b) / (2 e^{i beta} Y_f) with r_ij = (Y_i - Y_j) / (Y_i + Y_j):
//   r = [C (Y_o - Y_b) + i (S2 - Y_o Y_b S1)] / [C (Y_o + Y_b) - i (S2 + Y_o Y_b S1)],
// C = cos beta, S1 = sin(beta) / Y_f, S2 = Y_f sin(beta). These depend on the film only through
// Y_f^2 and beta^2, so the form stays exact through the critical angle of the film and for an
// evanescent film, and reduces to the bare outside/base interface for d = 0. For p
// polarization Y = cos / n, for s Y = n cos; S1 and S2 arrive precomputed.
OPENPBR_FUNC float openpbr_thin_film_exact_polarization(float cosine_term, float s1, float s2, float outside_admittance,
                                                        vec2 base_admittance)
{
    // With Y_b = p + i q: numerator = (C (Y_o - p) + Y_o S1 q) + i (S2 - C q - Y_o S1 p),
    // denominator = (C (Y_o + p) + Y_o S1 q) + i (C q - S2 - Y_o S1 p).
    const float outside_s1 = outside_admittance * s1;
    const vec2 numerator = vec2(cosine_term * (outside_admittance - base_admittance.x) + outside_s1 * base_admittance.y,
                                s2 - cosine_term * base_admittance.y - outside_s1 * base_admittance.x);
    const vec2 denominator = vec2(cosine_term * (outside_admittance + base_admittance.x) + outside_s1 * base_admittance.y,
                                  cosine_term * base_admittance.y - s2 - outside_s1 * base_admittance.x);
    const float denominator_norm = openpbr_complex_norm_squared(denominator);
    // Only at grazing incidence onto a grazing base wave can both vanish; that limit reflects all.
    return denominator_norm > 1e-30f ? openpbr_complex_norm_squared(numerator) / denominator_norm : 1.0f;
}

// Polarization-averaged reflectance of a stack whose film is evanescent, at wavenumber nu
// (um^-1). With beta = i b the form's cos beta -> cosh b and sin(beta)/beta -> sinh(b)/b; both
// are divided by cosh b (which cancels in r) so a thick film does not overflow, leaving
// C = 1 and tanh(b)/b.
OPENPBR_FUNC float openpbr_thin_film_evanescent_reflectance(OPENPBR_IN(OpenPBR_ThinFilmStack) stack, float nu)
{
    const float k0_d = OPENPBR_TWO_PI * nu * stack.thickness_um;
    const float b = k0_d * sqrt(max(-stack.film_normal_term, 0.0f));
    const float decay = exp(-2.0f * b);
    const float b_squared = b * b;
    // tanh(b)/b; the series avoids 1 - decay cancelling for small b.
    const float tanh_ratio = b < 0.05f ? 1.0f - b_squared * (1.0f / 3.0f) + b_squared * b_squared * (2.0f / 15.0f)
                                       : (1.0f - decay) / ((1.0f + decay) * b);
    const float s_common = k0_d * tanh_ratio;
    const float r_s = openpbr_thin_film_exact_polarization(1.0f, s_common, s_common * stack.film_normal_term,
                                                           stack.outside_admittance_s, stack.base_admittance_s);
    // cos_b / N = N cos_b / N^2.
    const float r_p = openpbr_thin_film_exact_polarization(
        1.0f, s_common * stack.film_ior_squared, s_common * stack.film_normal_term / stack.film_ior_squared,
        stack.outside_admittance_p, openpbr_complex_divide(stack.base_admittance_s, stack.base_ior_squared));
    return 0.5f * (r_s + r_p);
}

// ---- Spectral lobe average (Belcour & Barla's Fourier-domain integration) --------------------

struct OpenPBR_ThinFilmLobePhase OPENPBR_DIFFERENTIABLE
{
    vec2 phasor;            // e^{i 2 pi OPD nu_j}
    vec2 one_minus_phasor;  // 1 - phasor, exact near a zero phase
    float damping;          // g_j = exp(-(2 pi OPD sigma_j)^2 / 2)
};

OPENPBR_FUNC OpenPBR_ThinFilmLobePhase openpbr_thin_film_lobe_phase(float optical_path_difference_um,
                                                                    float spread_phase_variance, float nu, float sigma)
{
    // Half the phase, reduced to [0, pi): the phasor and 1 - phasor are then built from
    // sin and cos of it, 1 - e^{i phi} = 2 sin^2(phi/2) - i sin(phi).
    const float cycles = optical_path_difference_um * nu;
    const vec2 half_phase_sine_cosine = openpbr_sin_cos_pi(fract(cycles));
    const float sine = half_phase_sine_cosine.x;
    const float cosine = half_phase_sine_cosine.y;
    const float two_sine_squared = 2.0f * sine * sine;
    const float sine_phase = 2.0f * sine * cosine;
    // tau^2 = (2 pi)^2 (OPD^2 sigma^2 + spread^2 nu^2): the phase variance over the spectral
    // lobe and the microfacets.
    const float tau_squared =
        openpbr_square(OPENPBR_TWO_PI * optical_path_difference_um * sigma) + spread_phase_variance * (nu * nu);
    OpenPBR_ThinFilmLobePhase phase;
    phase.phasor = vec2(1.0f - two_sine_squared, sine_phase);
    phase.one_minus_phasor = vec2(two_sine_squared, -sine_phase);
    phase.damping = exp(-0.5f * min(tau_squared, 1e4f));
    return phase;
}

// N^2 and N cos_b = sqrt(N^2 - (n_o sin theta)^2) of a base, the two numbers the stack needs.
struct OpenPBR_ThinFilmBase OPENPBR_DIFFERENTIABLE
{
    vec2 ior_squared;
    vec2 normal_term;
};

// Conductor channel of complex IOR N = n + i k.
OPENPBR_FUNC OpenPBR_ThinFilmBase openpbr_thin_film_conductor_base(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs, float n,
                                                                   float k)
{
    const float n_clamped = openpbr_clamp_finite(n, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    const float k_clamped = openpbr_clamp_finite(k, 0.0f, OPENPBR_THIN_FILM_MAX_EXTINCTION);
    OpenPBR_ThinFilmBase base;
    base.ior_squared = vec2(n_clamped * n_clamped - k_clamped * k_clamped, 2.0f * n_clamped * k_clamped);
    base.normal_term = openpbr_complex_sqrt(
        vec2(openpbr_thin_film_normal_term(n_clamped, inputs.n_o, inputs.outside_normal_term) - k_clamped * k_clamped,
             base.ior_squared.y));
    return base;
}

OPENPBR_FUNC OpenPBR_ThinFilmStack openpbr_thin_film_conductor_stack(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs, float n,
                                                                     float k)
{
    const OpenPBR_ThinFilmBase base = openpbr_thin_film_conductor_base(inputs, n, k);
    return openpbr_thin_film_stack(inputs, base.ior_squared, base.normal_term);
}

// ---- What both forms of the full model share ----------------------------------------------

// Optical path difference 2 n_f d cos_f of the film (0 when it is evanescent).
OPENPBR_FUNC float openpbr_thin_film_optical_path_difference(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs)
{
    return 2.0f * openpbr_safe_sqrt(inputs.film_normal_term) * inputs.thickness_um;
}

// The film over a dielectric base (real IOR dielectric_ior), over a conductor base (complex IOR
// base_n + i base_k per RGB channel), or over both at once: the base layer's two Fresnel
// factors at one microfacet angle (spec "Thin-film iridescence": the film lies over the metal
// and the dielectric), which share the film's harmonics. A base that is not wanted returns 0.
struct OpenPBR_ThinFilmBasePair OPENPBR_DIFFERENTIABLE
{
    vec3 dielectric;
    vec3 conductor;
};

// The pair before any stack is evaluated: 1 for each wanted base (what grazing incidence and
// total internal reflection at a dielectric base give), 0 for a base that is not wanted.
OPENPBR_FUNC OpenPBR_ThinFilmBasePair openpbr_thin_film_total_reflection_pair(bool with_dielectric, bool with_conductor)
{
    OpenPBR_ThinFilmBasePair pair;
    pair.dielectric = vec3(with_dielectric ? 1.0f : 0.0f);
    pair.conductor = vec3(with_conductor ? 1.0f : 0.0f);
    return pair;
}

#if OPENPBR_FILM_FOUR_LANES

// ---- The full model: every base at once, in four lanes -----------------------------------------
//
// One film evaluation sets up the four stacks that differ in their base side by side in the
// lanes of vec4s: x, y, z the conductor's red, green and blue channels, w the dielectric base
// (whose values are real). The six spectral lobes' phases are computed once, lobes 0-3 in the
// lanes of one vec4 and lobes 4, 5 in x, y of a second (its z, w carry no weight), and read by
// the harmonics and the closed-form tail of every stack and polarization. In C++ with GLM's SIMD
// the lanes are SSE registers (interop/openpbr_interop_cpp.h); a GPU build may select this form
// too (OPENPBR_FILM_FOUR_LANES=1), at a longer driver build: llvmpipe's build of the full
// module took 52 % more instructions.

// Four numbers per spectral lobe, lobes 0-3 in the lanes of `low` and 4, 5 in x, y of `high`.
// A loop over the lobes reads lobe j from lane x of `low` at its step j, each step shifting
// the queue by one lobe (openpbr_thin_film_lobe_queue_next): one vector shuffle where reading
// lane j by index would be a chain of selects in the GPU code.
struct OpenPBR_ThinFilmLobeQueue OPENPBR_DIFFERENTIABLE
{
    vec4 low;
    vec4 high;
};

OPENPBR_FUNC OpenPBR_ThinFilmLobeQueue openpbr_thin_film_lobe_queue(vec4 low, vec4 high)
{
    OpenPBR_ThinFilmLobeQueue queue;
    queue.low = low;
    queue.high = high;
    return queue;
}

OPENPBR_FUNC OpenPBR_ThinFilmLobeQueue openpbr_thin_film_lobe_queue_next(OPENPBR_IN(OpenPBR_ThinFilmLobeQueue) queue)
{
    return openpbr_thin_film_lobe_queue(vec4(queue.low.y, queue.low.z, queue.low.w, queue.high.x),
                                        vec4(queue.high.y, queue.high.z, queue.high.w, 0.0f));
}

// The lobes' constants in queue form: centres, deviations and each channel's weights.
OPENPBR_FUNC OpenPBR_ThinFilmLobeQueue openpbr_thin_film_lobe_centres()
{
    return openpbr_thin_film_lobe_queue(
        vec4(OPENPBR_THIN_FILM_LOBE0_NU, OPENPBR_THIN_FILM_LOBE1_NU, OPENPBR_THIN_FILM_LOBE2_NU, OPENPBR_THIN_FILM_LOBE3_NU),
        vec4(OPENPBR_THIN_FILM_LOBE4_NU, OPENPBR_THIN_FILM_LOBE5_NU, OPENPBR_THIN_FILM_LOBE4_NU,
             OPENPBR_THIN_FILM_LOBE5_NU));
}

OPENPBR_FUNC OpenPBR_ThinFilmLobeQueue openpbr_thin_film_lobe_deviations()
{
    return openpbr_thin_film_lobe_queue(vec4(OPENPBR_THIN_FILM_LOBE0_SIGMA, OPENPBR_THIN_FILM_LOBE1_SIGMA,
                                             OPENPBR_THIN_FILM_LOBE2_SIGMA, OPENPBR_THIN_FILM_LOBE3_SIGMA),
                                        vec4(OPENPBR_THIN_FILM_LOBE4_SIGMA, OPENPBR_THIN_FILM_LOBE5_SIGMA,
                                             OPENPBR_THIN_FILM_LOBE4_SIGMA, OPENPBR_THIN_FILM_LOBE5_SIGMA));
}

// Channel `channel` (0-2) of every lobe's weight vec3 (OPENPBR_THIN_FILM_LOBEk_WEIGHT).
OPENPBR_FUNC OpenPBR_ThinFilmLobeQueue openpbr_thin_film_lobe_weights(int channel)
{
    return openpbr_thin_film_lobe_queue(vec4(openpbr_channel_of(OPENPBR_THIN_FILM_LOBE0_WEIGHT, channel),
                                             openpbr_channel_of(OPENPBR_THIN_FILM_LOBE1_WEIGHT, channel),
                                             openpbr_channel_of(OPENPBR_THIN_FILM_LOBE2_WEIGHT, channel),
                                             openpbr_channel_of(OPENPBR_THIN_FILM_LOBE3_WEIGHT, channel)),
                                        vec4(openpbr_channel_of(OPENPBR_THIN_FILM_LOBE4_WEIGHT, channel),
                                             openpbr_channel_of(OPENPBR_THIN_FILM_LOBE5_WEIGHT, channel), 0.0f, 0.0f));
}

// The largest sum of a channel's absolute lobe weights, e.g. 2.49 (red): what the film's
// harmonic m can reach in a channel, |H_c(m)| <= sum_j |W_cj| g_j^(m^2).
OPENPBR_FUNC float openpbr_thin_film_largest_weight_sum()
{
    const vec3 sums = abs(OPENPBR_THIN_FILM_LOBE0_WEIGHT) + abs(OPENPBR_THIN_FILM_LOBE1_WEIGHT) +
                      abs(OPENPBR_THIN_FILM_LOBE2_WEIGHT) + abs(OPENPBR_THIN_FILM_LOBE3_WEIGHT) +
                      abs(OPENPBR_THIN_FILM_LOBE4_WEIGHT) + abs(OPENPBR_THIN_FILM_LOBE5_WEIGHT);
    return max(max(sums.x, sums.y), sums.z);
}

// The phases of four lobes (as openpbr_thin_film_lobe_phase, lane by lane).
struct OpenPBR_ThinFilmLobeLanes OPENPBR_DIFFERENTIABLE
{
    vec4 phasor_real;            // cos(2 pi OPD nu_j)
    vec4 phasor_imaginary;       // sin(2 pi OPD nu_j)
    vec4 one_minus_phasor_real;  // 1 - cos, as 2 sin^2 of the half phase (exact near a zero phase)
    vec4 damping;                // g_j
};

OPENPBR_FUNC OpenPBR_ThinFilmLobeLanes openpbr_thin_film_lobe_lanes(float optical_path_difference_um,
                                                                    float spread_phase_variance, vec4 nu, vec4 sigma)
{
    // Half the phase, reduced to [0, pi) (cycles >= 0).
    const vec4 half_turn = fract(optical_path_difference_um * nu);
    const vec4 sine = openpbr_sin_pi(half_turn);
    const vec4 cosine = openpbr_cos_pi(half_turn);
    // tau^2 = (2 pi)^2 (OPD^2 sigma^2 + spread^2 nu^2): the phase variance over the spectral
    // lobe and the microfacets.
    const vec4 path_sigma = OPENPBR_TWO_PI * optical_path_difference_um * sigma;
    const vec4 tau_squared = path_sigma * path_sigma + spread_phase_variance * (nu * nu);
    OpenPBR_ThinFilmLobeLanes lanes;
    lanes.one_minus_phasor_real = 2.0f * sine * sine;
    lanes.phasor_real = vec4(1.0f) - lanes.one_minus_phasor_real;
    lanes.phasor_imaginary = 2.0f * sine * cosine;
    lanes.damping = exp(-0.5f * min(tau_squared, vec4(1e4f)));
    return lanes;
}

// Harmonic m of four lobes, advanced one m at a time: e^{i m delta_j} and g_j^(m^2), with
// g^((m+1)^2) = g^(m^2) g^(2m+1).
struct OpenPBR_ThinFilmHarmonicLanes OPENPBR_DIFFERENTIABLE
{
    vec4 power_real;       // Re e^{i m delta_j}
    vec4 power_imaginary;  // Im e^{i m delta_j}
    vec4 damping;          // g_j^(m^2)
    vec4 damping_step;     // g_j^(2m+1): the next harmonic's factor
};

OPENPBR_FUNC OpenPBR_ThinFilmHarmonicLanes openpbr_thin_film_harmonic_lanes_zero(OPENPBR_IN(OpenPBR_ThinFilmLobeLanes) lobes)
{
    OpenPBR_ThinFilmHarmonicLanes harmonic;
    harmonic.power_real = vec4(1.0f);
    harmonic.power_imaginary = vec4(0.0f);
    harmonic.damping = vec4(1.0f);
    harmonic.damping_step = lobes.damping;
    return harmonic;
}

OPENPBR_FUNC OpenPBR_ThinFilmHarmonicLanes openpbr_thin_film_harmonic_lanes_next(OPENPBR_IN(OpenPBR_ThinFilmHarmonicLanes)
                                                                                     harmonic,
                                                                                 OPENPBR_IN(OpenPBR_ThinFilmLobeLanes) lobes)
{
    OpenPBR_ThinFilmHarmonicLanes next;
    next.power_real = harmonic.power_real * lobes.phasor_real - harmonic.power_imaginary * lobes.phasor_imaginary;
    next.power_imaginary = harmonic.power_real * lobes.phasor_imaginary + harmonic.power_imaginary * lobes.phasor_real;
    next.damping = harmonic.damping * harmonic.damping_step;
    next.damping_step = harmonic.damping_step * (lobes.damping * lobes.damping);
    return next;
}

// The film's harmonic H(m) = sum_j W_j g_j^(m^2) e^{i m delta_j} in the RGB lanes x, y, z (w 0),
// real part (imaginary false) or imaginary part, from the six lobes' lanes.
OPENPBR_FUNC vec4 openpbr_thin_film_harmonic_sum(OPENPBR_IN(OpenPBR_ThinFilmHarmonicLanes) low,
                                                 OPENPBR_IN(OpenPBR_ThinFilmHarmonicLanes) high, bool imaginary)
{
    const vec4 low_value = low.damping * (imaginary ? low.power_imaginary : low.power_real);
    const vec4 high_value = high.damping * (imaginary ? high.power_imaginary : high.power_real);
    return vec4(OPENPBR_THIN_FILM_LOBE0_WEIGHT, 0.0f) * low_value.x +
           vec4(OPENPBR_THIN_FILM_LOBE1_WEIGHT, 0.0f) * low_value.y +
           vec4(OPENPBR_THIN_FILM_LOBE2_WEIGHT, 0.0f) * low_value.z +
           vec4(OPENPBR_THIN_FILM_LOBE3_WEIGHT, 0.0f) * low_value.w +
           vec4(OPENPBR_THIN_FILM_LOBE4_WEIGHT, 0.0f) * high_value.x +
           vec4(OPENPBR_THIN_FILM_LOBE5_WEIGHT, 0.0f) * high_value.y;
}

// The outside -> film interface of one polarization, r12 = (a1 - b1) / (a1 + b1) (real a1,
// b1 >= 0): the same for every base.
struct OpenPBR_ThinFilmTopInterface OPENPBR_DIFFERENTIABLE
{
    float a;
    float b;
    float inverse_sum;    // 1 / (a1 + b1)
    float reflection;     // r12
    float reflectance;    // R12
    float transmittance;  // T12 = 1 - R12, computed directly (it vanishes at grazing incidence)
};

OPENPBR_FUNC OpenPBR_ThinFilmTopInterface openpbr_thin_film_top_interface(float a1, float b1)
{
    OpenPBR_ThinFilmTopInterface top;
    top.a = a1;
    top.b = b1;
    top.inverse_sum = 1.0f / max(a1 + b1, 1e-30f);
    top.reflection = (a1 - b1) * top.inverse_sum;
    top.reflectance = top.reflection * top.reflection;
    top.transmittance = 4.0f * a1 * b1 * top.inverse_sum * top.inverse_sum;
    return top;
}

// One polarization's Airy series (as OpenPBR_ThinFilmPolarization) of the four stacks, one per
// lane: rho and 1 - rho are complex (real and imaginary lanes).
struct OpenPBR_ThinFilmSeriesLanes OPENPBR_DIFFERENTIABLE
{
    vec4 mean;       // C0
    vec4 amplitude;  // A
    vec4 rho_real;   // rho = r21 r23
    vec4 rho_imaginary;
    vec4 one_minus_rho_real;  // 1 - rho, without cancellation
    vec4 one_minus_rho_imaginary;
    vec4 rho_magnitude;  // |rho|
    vec4 bound_factor;   // 2 |A| / (1 - |rho|): harmonics m > M sum to at most this times |rho|^(M+1)
    vec4 tail_bound;     // 2 |A| |rho|^5 / (1 - |rho|): bounds the harmonics m >= 5 (before damping)
};

// The series of the four stacks reached through film -> base coefficients
// r23 = (a2 - b2) / (a2 + b2), complex per lane, as openpbr_thin_film_polarization.
OPENPBR_FUNC OpenPBR_ThinFilmSeriesLanes openpbr_thin_film_series_lanes(OPENPBR_IN(OpenPBR_ThinFilmTopInterface) top,
                                                                        vec4 a2_real, vec4 a2_imaginary, vec4 b2_real,
                                                                        vec4 b2_imaginary)
{
    // Quotients by a2 + b2 as multiplications by conj(a2 + b2) / |a2 + b2|^2 (one division).
    const vec4 sum_real = a2_real + b2_real;
    const vec4 sum_imaginary = a2_imaginary + b2_imaginary;
    const vec4 inverse_sum_norm = vec4(1.0f) / max(sum_real * sum_real + sum_imaginary * sum_imaginary, vec4(1e-30f));
    const vec4 difference_real = a2_real - b2_real;
    const vec4 difference_imaginary = a2_imaginary - b2_imaginary;
    const vec4 r23_real = (difference_real * sum_real + difference_imaginary * sum_imaginary) * inverse_sum_norm;
    const vec4 r23_imaginary = (difference_imaginary * sum_real - difference_real * sum_imaginary) * inverse_sum_norm;
    const vec4 reflectance_23 = r23_real * r23_real + r23_imaginary * r23_imaginary;
    // 1 - |r23|^2 = 4 Re(a2 conj(b2)) / |a2 + b2|^2: the power entering the base.
    const vec4 transmittance_23 =
        max(4.0f * (a2_real * b2_real + a2_imaginary * b2_imaginary) * inverse_sum_norm, vec4(0.0f));
    // 1 - R12 R23 = T12 + R12 T23 (using R12 + T12 = 1), without cancellation.
    const vec4 inverse_denominator = vec4(1.0f) / max(top.transmittance + top.reflectance * transmittance_23, vec4(1e-30f));
    OpenPBR_ThinFilmSeriesLanes series;
    series.mean = top.reflectance + top.transmittance * top.transmittance * reflectance_23 * inverse_denominator;
    series.amplitude = -top.transmittance * transmittance_23 * inverse_denominator;
    series.rho_real = -top.reflection * r23_real;
    series.rho_imaginary = -top.reflection * r23_imaginary;
    // 1 + r12 r23 = 2 (a1 a2 + b1 b2) / ((a1 + b1)(a2 + b2)).
    const vec4 scale = 2.0f * inverse_sum_norm * top.inverse_sum;
    const vec4 numerator_real = top.a * a2_real + top.b * b2_real;
    const vec4 numerator_imaginary = top.a * a2_imaginary + top.b * b2_imaginary;
    series.one_minus_rho_real = (numerator_real * sum_real + numerator_imaginary * sum_imaginary) * scale;
    series.one_minus_rho_imaginary = (numerator_imaginary * sum_real - numerator_real * sum_imaginary) * scale;
    // |rho|^2 = R12 R23 and 1 / (1 - |rho|) = (1 + |rho|) / (1 - R12 R23), without cancellation.
    const vec4 rho_squared = top.reflectance * reflectance_23;
    series.rho_magnitude = sqrt(rho_squared);
    series.bound_factor = 2.0f * abs(series.amplitude) * (vec4(1.0f) + series.rho_magnitude) * inverse_denominator;
    series.tail_bound = series.bound_factor * (rho_squared * rho_squared) * series.rho_magnitude;
    return series;
}

// The largest of a vec4's lanes.
OPENPBR_FUNC float openpbr_largest_lane(vec4 v) { return max(max(v.x, v.y), max(v.z, v.w)); }

// A rho^m of both polarizations in the four lanes, complex, advanced one m at a time.
struct OpenPBR_ThinFilmAmplitudeLanes OPENPBR_DIFFERENTIABLE
{
    vec4 s_real;
    vec4 s_imaginary;
    vec4 p_real;
    vec4 p_imaginary;
};

OPENPBR_FUNC OpenPBR_ThinFilmAmplitudeLanes openpbr_thin_film_amplitude_lanes_next(OPENPBR_IN(OpenPBR_ThinFilmAmplitudeLanes)
                                                                                       powers,
                                                                                   OPENPBR_IN(OpenPBR_ThinFilmSeriesLanes) s,
                                                                                   OPENPBR_IN(OpenPBR_ThinFilmSeriesLanes) p)
{
    OpenPBR_ThinFilmAmplitudeLanes next;
    next.s_real = powers.s_real * s.rho_real - powers.s_imaginary * s.rho_imaginary;
    next.s_imaginary = powers.s_real * s.rho_imaginary + powers.s_imaginary * s.rho_real;
    next.p_real = powers.p_real * p.rho_real - powers.p_imaginary * p.rho_imaginary;
    next.p_imaginary = powers.p_real * p.rho_imaginary + powers.p_imaginary * p.rho_real;
    return next;
}

// One polarization's closed-form tail m >= 5 of one lobe (as openpbr_thin_film_lobe_tail) in the
// four stacks: Re(A rho^5 g^25 e^{5 i delta} / (1 - g^15 rho e^{i delta})), from the lobe's
// numerator g^25 e^{5 i delta} and complement 1 - g^15 e^{i delta}, with
// 1 - g^15 z = (1 - rho) + rho (1 - g^15 e^{i delta}), each part without cancellation.
OPENPBR_FUNC vec4 openpbr_thin_film_tail_lanes(OPENPBR_IN(OpenPBR_ThinFilmSeriesLanes) series, vec4 amplitude_rho_5_real,
                                               vec4 amplitude_rho_5_imaginary, float numerator_real,
                                               float numerator_imaginary, float complement_real, float complement_imaginary)
{
    const vec4 denominator_real =
        series.one_minus_rho_real + series.rho_real * complement_real - series.rho_imaginary * complement_imaginary;
    const vec4 denominator_imaginary =
        series.one_minus_rho_imaginary + series.rho_real * complement_imaginary + series.rho_imaginary * complement_real;
    const vec4 top_real = amplitude_rho_5_real * numerator_real - amplitude_rho_5_imaginary * numerator_imaginary;
    const vec4 top_imaginary = amplitude_rho_5_real * numerator_imaginary + amplitude_rho_5_imaginary * numerator_real;
    return (top_real * denominator_real + top_imaginary * denominator_imaginary) /
           max(denominator_real * denominator_real + denominator_imaginary * denominator_imaginary, vec4(1e-30f));
}

// One polarization's exact reflectance of the four stacks with an evanescent film at one
// wavenumber (openpbr_thin_film_exact_polarization with C = 1, lane by lane).
OPENPBR_FUNC vec4 openpbr_thin_film_exact_lanes(float s1, float s2, float outside_admittance, vec4 base_real,
                                                vec4 base_imaginary)
{
    const float outside_s1 = outside_admittance * s1;
    const vec4 numerator_real = (outside_admittance - base_real) + outside_s1 * base_imaginary;
    const vec4 numerator_imaginary = (s2 - base_imaginary) - outside_s1 * base_real;
    const vec4 denominator_real = (outside_admittance + base_real) + outside_s1 * base_imaginary;
    const vec4 denominator_imaginary = (base_imaginary - s2) - outside_s1 * base_real;
    const vec4 numerator_norm = numerator_real * numerator_real + numerator_imaginary * numerator_imaginary;
    const vec4 denominator_norm = denominator_real * denominator_real + denominator_imaginary * denominator_imaginary;
    // Only at grazing incidence onto a grazing base wave can both vanish; that limit reflects all
    // (a select by arithmetic: the ratio is finite, the mask 0 or 1).
    const vec4 valid = step(vec4(1e-30f), denominator_norm);
    return min(numerator_norm / max(denominator_norm, vec4(1e-30f)), vec4(1.0f)) * valid + (vec4(1.0f) - valid);
}

// The bases of the four stacks (lanes as above): N^2 and the admittance N cos_b =
// sqrt(N^2 - (n_o sin theta)^2) (principal root), complex.
struct OpenPBR_ThinFilmBaseLanes OPENPBR_DIFFERENTIABLE
{
    vec4 ior_squared_real;
    vec4 ior_squared_imaginary;
    vec4 admittance_real;
    vec4 admittance_imaginary;
};

// The lanes' principal square roots of a + i b with b >= 0 in every lane, as
// openpbr_complex_sqrt: the larger part from sqrt((|a| + |z|) / 2), the other from b / 2 over
// it, put in place by an arithmetic select on the sign of a.
OPENPBR_FUNC OpenPBR_ThinFilmBaseLanes openpbr_thin_film_admittance_lanes(vec4 real_part, vec4 imaginary_part)
{
    const vec4 magnitude = sqrt(real_part * real_part + imaginary_part * imaginary_part);
    const vec4 larger = sqrt(0.5f * (magnitude + abs(real_part)));
    const vec4 smaller = 0.5f * imaginary_part / max(larger, vec4(1e-30f));
    const vec4 nonnegative = step(vec4(0.0f), real_part);
    OpenPBR_ThinFilmBaseLanes bases;
    bases.admittance_real = larger * nonnegative + smaller * (vec4(1.0f) - nonnegative);
    bases.admittance_imaginary = smaller * nonnegative + larger * (vec4(1.0f) - nonnegative);
    return bases;
}

// The four stacks' reflectances: RGB of the conductor in x, y, z of `conductor`, of the
// dielectric in x, y, z of `dielectric`.
struct OpenPBR_ThinFilmLaneSums OPENPBR_DIFFERENTIABLE
{
    vec4 conductor;
    vec4 dielectric;
};

// What the propagating film's series leave to a loop over the lobes: the closed-form tail's
// inputs per lobe (in queues) and per stack (in lanes, as everywhere in this form), and the
// stacks that take it.
struct OpenPBR_ThinFilmTail OPENPBR_DIFFERENTIABLE
{
    OpenPBR_ThinFilmLobeQueue numerator_real;  // g^25 e^{5 i delta}
    OpenPBR_ThinFilmLobeQueue numerator_imaginary;
    OpenPBR_ThinFilmLobeQueue complement_real;  // 1 - g^15 e^{i delta}
    OpenPBR_ThinFilmLobeQueue complement_imaginary;
    OpenPBR_ThinFilmAmplitudeLanes amplitude_rho_5;  // A rho^5
    vec4 stacks;                                     // 1 for the stacks that take the tail, else 0
};

// The propagating film's series summed over its harmonics: R = C0 + sum_pol sum_m Re(A rho^m H(m))
// with the film's harmonics H(m) as far as the wanted stacks need them (see the top), and the
// tail's inputs where a stack needs them (tail.stacks, all 0 where none does; the caller sets
// the rest).
OPENPBR_FUNC OpenPBR_ThinFilmLaneSums openpbr_thin_film_harmonic_sums(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs,
                                                                      OPENPBR_IN(OpenPBR_ThinFilmSeriesLanes) s,
                                                                      OPENPBR_IN(OpenPBR_ThinFilmSeriesLanes) p, vec4 wanted,
                                                                      OPENPBR_OUT(OpenPBR_ThinFilmTail) tail)
{
    const float optical_path_difference_um = openpbr_thin_film_optical_path_difference(inputs);
    const float spread_phase_variance = openpbr_thin_film_spread_phase_variance(inputs.optical_path_spread_um);
    const OpenPBR_ThinFilmLobeQueue centres = openpbr_thin_film_lobe_centres();
    const OpenPBR_ThinFilmLobeQueue deviations = openpbr_thin_film_lobe_deviations();
    const OpenPBR_ThinFilmLobeLanes low =
        openpbr_thin_film_lobe_lanes(optical_path_difference_um, spread_phase_variance, centres.low, deviations.low);
    const OpenPBR_ThinFilmLobeLanes high =
        openpbr_thin_film_lobe_lanes(optical_path_difference_um, spread_phase_variance, centres.high, deviations.high);

    // How many harmonics the wanted stacks need: harmonics m > M add at most
    // W K P^(M+1) g^((M+1)^2) to a channel, with W the largest channel weight sum, K and P the
    // largest bound factor and |rho| of the wanted stacks and g the largest lobe damping. M is
    // the smallest in 0..4 where that is at most a fifth of OPENPBR_THIN_FILM_TRUNCATION_ERROR
    // (4 where none is). The tail runs only where M is 4: its bound, K P^5 g^25, is below M = 3's.
    const float damping = max(openpbr_largest_lane(low.damping), max(high.damping.x, high.damping.y));
    const float bound_factor = openpbr_largest_lane(max(s.bound_factor, p.bound_factor) * wanted);
    const float rho_magnitude = openpbr_largest_lane(max(s.rho_magnitude, p.rho_magnitude) * wanted);
    const float damping_4 = openpbr_square(damping * damping);
    const float damping_9 = damping_4 * damping_4 * damping;
    const float damping_16 = damping_4 * damping_4 * damping_4 * damping_4;
    const float first_bound = openpbr_thin_film_largest_weight_sum() * bound_factor * rho_magnitude;
    const float rho_squared = rho_magnitude * rho_magnitude;
    const float drop_threshold = 0.2f * OPENPBR_THIN_FILM_TRUNCATION_ERROR;
    const int harmonic_count = int(first_bound * damping > drop_threshold) +
                               int(first_bound * rho_magnitude * damping_4 > drop_threshold) +
                               int(first_bound * rho_squared * damping_9 > drop_threshold) +
                               int(first_bound * rho_squared * rho_magnitude * damping_16 > drop_threshold);

    OpenPBR_ThinFilmLaneSums sums;
    sums.conductor = 0.5f * (s.mean + p.mean);
    sums.dielectric = vec4(sums.conductor.w);
    OpenPBR_ThinFilmHarmonicLanes low_harmonic = openpbr_thin_film_harmonic_lanes_zero(low);
    OpenPBR_ThinFilmHarmonicLanes high_harmonic = openpbr_thin_film_harmonic_lanes_zero(high);
    OpenPBR_ThinFilmAmplitudeLanes powers;  // A rho^m
    powers.s_real = s.amplitude;
    powers.s_imaginary = vec4(0.0f);
    powers.p_real = p.amplitude;
    powers.p_imaginary = vec4(0.0f);
    // At most four steps (harmonic_count, above).
    for (int harmonic = 1; harmonic <= harmonic_count; ++harmonic)
    {
        low_harmonic = openpbr_thin_film_harmonic_lanes_next(low_harmonic, low);
        high_harmonic = openpbr_thin_film_harmonic_lanes_next(high_harmonic, high);
        powers = openpbr_thin_film_amplitude_lanes_next(powers, s, p);
        const vec4 harmonic_real = openpbr_thin_film_harmonic_sum(low_harmonic, high_harmonic, false);
        const vec4 harmonic_imaginary = openpbr_thin_film_harmonic_sum(low_harmonic, high_harmonic, true);
        // Lane c of the conductor reads channel c's harmonic; the dielectric's rho is real.
        sums.conductor +=
            (powers.s_real + powers.p_real) * harmonic_real - (powers.s_imaginary + powers.p_imaginary) * harmonic_imaginary;
        sums.dielectric += (powers.s_real.w + powers.p_real.w) * harmonic_real;
    }

    // The tail in the stacks where the harmonics m >= 5 may exceed OPENPBR_THIN_FILM_TRUNCATION_ERROR
    // (the stacks one film evaluation one stack at a time gave it to), from each lobe's
    // g^25 e^{5 i delta} = g^16 e^{4 i delta} g^9 e^{i delta} and
    // 1 - g^15 e^{i delta} = (1 - e^{i delta}) + (1 - g^9 g^6) e^{i delta}.
    const vec4 tail_bound = max(s.tail_bound, p.tail_bound) * (damping_16 * damping_9) * wanted;
    tail.stacks = step(vec4(OPENPBR_THIN_FILM_TRUNCATION_ERROR), tail_bound) * float(harmonic_count == 4);
    if (openpbr_largest_lane(tail.stacks) <= 0.0f)
    {
        return sums;
    }
    tail.amplitude_rho_5 = openpbr_thin_film_amplitude_lanes_next(powers, s, p);
    const OpenPBR_ThinFilmHarmonicLanes low_fifth = openpbr_thin_film_harmonic_lanes_next(low_harmonic, low);
    const OpenPBR_ThinFilmHarmonicLanes high_fifth = openpbr_thin_film_harmonic_lanes_next(high_harmonic, high);
    tail.numerator_real =
        openpbr_thin_film_lobe_queue(low_fifth.damping * low_fifth.power_real, high_fifth.damping * high_fifth.power_real);
    tail.numerator_imaginary = openpbr_thin_film_lobe_queue(low_fifth.damping * low_fifth.power_imaginary,
                                                            high_fifth.damping * high_fifth.power_imaginary);
    const vec4 low_damping_2 = low.damping * low.damping;
    const vec4 high_damping_2 = high.damping * high.damping;
    const vec4 low_ratio = low_harmonic.damping_step * (low_damping_2 * low_damping_2 * low_damping_2);
    const vec4 high_ratio = high_harmonic.damping_step * (high_damping_2 * high_damping_2 * high_damping_2);
    tail.complement_real =
        openpbr_thin_film_lobe_queue(low.one_minus_phasor_real + (vec4(1.0f) - low_ratio) * low.phasor_real,
                                     high.one_minus_phasor_real + (vec4(1.0f) - high_ratio) * high.phasor_real);
    tail.complement_imaginary =
        openpbr_thin_film_lobe_queue(-low_ratio * low.phasor_imaginary, -high_ratio * high.phasor_imaginary);
    return sums;
}

// k0 d tanh(b)/b per lobe, b = k0 d sqrt((n_o sin theta)^2 - n_f^2), k0 = 2 pi nu: S of an
// evanescent film's characteristic-matrix form (openpbr_thin_film_evanescent_reflectance), for
// the four lobes of `nu`.
OPENPBR_FUNC vec4 openpbr_thin_film_evanescent_lanes(vec4 nu, float thickness_um, float decay_root)
{
    const vec4 k0_d = OPENPBR_TWO_PI * nu * thickness_um;
    const vec4 b = k0_d * decay_root;
    const vec4 decay = exp(-2.0f * b);
    const vec4 b_squared = b * b;
    // tanh(b)/b; the series below b = 0.05 avoids 1 - decay cancelling (an arithmetic select).
    const vec4 series = vec4(1.0f) - b_squared * (1.0f / 3.0f) + b_squared * b_squared * (2.0f / 15.0f);
    const vec4 ratio = (vec4(1.0f) - decay) / ((vec4(1.0f) + decay) * max(b, vec4(1e-30f)));
    const vec4 large = step(vec4(0.05f), b);
    return k0_d * (ratio * large + series * (vec4(1.0f) - large));
}

OPENPBR_FUNC OpenPBR_ThinFilmBasePair openpbr_thin_film_fresnel_bases(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs,
                                                                      bool with_dielectric, float dielectric_ior,
                                                                      bool with_conductor, vec3 base_n, vec3 base_k)
{
    OpenPBR_ThinFilmBasePair pair = openpbr_thin_film_total_reflection_pair(with_dielectric, with_conductor);
    const float n_b = openpbr_clamp_finite(dielectric_ior, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    const float dielectric_normal_term = openpbr_thin_film_normal_term(n_b, inputs.n_o, inputs.outside_normal_term);
    if (inputs.cos_o <= 0.0f)
    {
        return pair;
    }
    // Total internal reflection at a dielectric base reflects everything (pair.dielectric 1).
    const bool dielectric = with_dielectric && dielectric_normal_term > 0.0f;
    const vec4 wanted = vec4(vec3(with_conductor ? 1.0f : 0.0f), dielectric ? 1.0f : 0.0f);
    // N^2 and N cos_b: the conductor's from n + i k, the dielectric's real (w).
    const vec3 n = openpbr_clamp_finite(base_n, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    const vec3 k = openpbr_clamp_finite(base_k, 0.0f, OPENPBR_THIN_FILM_MAX_EXTINCTION);
    // Re(N^2) - (n_o sin theta)^2 = (n - n_o)(n + n_o) + (n_o cos)^2 - k^2 (openpbr_thin_film_normal_term).
    OpenPBR_ThinFilmBaseLanes bases = openpbr_thin_film_admittance_lanes(
        vec4((n - inputs.n_o) * (n + inputs.n_o) + inputs.outside_normal_term - k * k, dielectric_normal_term),
        vec4(2.0f * n * k, 0.0f));
    bases.ior_squared_real = vec4(n * n - k * k, n_b * n_b);
    bases.ior_squared_imaginary = vec4(2.0f * n * k, 0.0f);

    const bool evanescent = inputs.film_normal_term <= 0.0f;
    const float cos_f = openpbr_safe_sqrt(inputs.film_normal_term) / inputs.n_f;
    const float film_term = inputs.n_f * cos_f;
    // s: r_ij = (n_i cos_i - n_j cos_j) / (n_i cos_i + n_j cos_j);
    // p: r_ij = (n_j cos_i - n_i cos_j) / (n_j cos_i + n_i cos_j), with the film -> base pair
    // multiplied through by N so that only N^2 and N cos_b appear.
    const OpenPBR_ThinFilmSeriesLanes s =
        openpbr_thin_film_series_lanes(openpbr_thin_film_top_interface(inputs.n_o * inputs.cos_o, film_term),
                                       vec4(film_term), vec4(0.0f), bases.admittance_real, bases.admittance_imaginary);
    const OpenPBR_ThinFilmSeriesLanes p = openpbr_thin_film_series_lanes(
        openpbr_thin_film_top_interface(inputs.n_f * inputs.cos_o, inputs.n_o * cos_f), bases.ior_squared_real * cos_f,
        bases.ior_squared_imaginary * cos_f, inputs.n_f * bases.admittance_real, inputs.n_f * bases.admittance_imaginary);
    OpenPBR_ThinFilmTail tail;
    tail.numerator_real = openpbr_thin_film_lobe_queue(vec4(0.0f), vec4(0.0f));
    tail.numerator_imaginary = tail.numerator_real;
    tail.complement_real = tail.numerator_real;
    tail.complement_imaginary = tail.numerator_real;
    tail.amplitude_rho_5.s_real = vec4(0.0f);
    tail.amplitude_rho_5.s_imaginary = vec4(0.0f);
    tail.amplitude_rho_5.p_real = vec4(0.0f);
    tail.amplitude_rho_5.p_imaginary = vec4(0.0f);
    tail.stacks = vec4(1.0f);
    OpenPBR_ThinFilmLaneSums sums;
    sums.conductor = vec4(0.0f);
    sums.dielectric = vec4(0.0f);
    if (evanescent)
    {
        // No fringes: every lobe is evaluated exactly at its centre in the loop below, S in the
        // numerator's queue.
        const float decay_root = sqrt(max(-inputs.film_normal_term, 0.0f));
        const OpenPBR_ThinFilmLobeQueue centres = openpbr_thin_film_lobe_centres();
        tail.numerator_real =
            openpbr_thin_film_lobe_queue(openpbr_thin_film_evanescent_lanes(centres.low, inputs.thickness_um, decay_root),
                                         openpbr_thin_film_evanescent_lanes(centres.high, inputs.thickness_um, decay_root));
    }
    else
    {
        sums = openpbr_thin_film_harmonic_sums(inputs, s, p, wanted, tail);
    }
    if (openpbr_largest_lane(tail.stacks) > 0.0f)
    {
        // cos_b / N = N cos_b / N^2, the p admittance of the evanescent film's base.
        const vec4 ior_norm =
            max(bases.ior_squared_real * bases.ior_squared_real + bases.ior_squared_imaginary * bases.ior_squared_imaginary,
                vec4(1e-30f));
        const vec4 admittance_p_real =
            (bases.admittance_real * bases.ior_squared_real + bases.admittance_imaginary * bases.ior_squared_imaginary) /
            ior_norm;
        const vec4 admittance_p_imaginary =
            (bases.admittance_imaginary * bases.ior_squared_real - bases.admittance_real * bases.ior_squared_imaginary) /
            ior_norm;
        const float film_ior_squared = inputs.n_f * inputs.n_f;
        OpenPBR_ThinFilmLobeQueue red = openpbr_thin_film_lobe_weights(0);
        OpenPBR_ThinFilmLobeQueue green = openpbr_thin_film_lobe_weights(1);
        OpenPBR_ThinFilmLobeQueue blue = openpbr_thin_film_lobe_weights(2);
        OpenPBR_ThinFilmLaneSums lobe_sums;
        lobe_sums.conductor = vec4(0.0f);
        lobe_sums.dielectric = vec4(0.0f);
        // Six steps, one per spectral lobe (lane x of each queue).
        OPENPBR_ROLLED_ON_GPU
        for (int lobe_index = 0; lobe_index < 6; ++lobe_index)
        {
            vec4 values = vec4(0.0f);
            if (evanescent)
            {
                const float factor = tail.numerator_real.low.x;  // S = k0 d tanh(b)/b
                values = 0.5f *
                         (openpbr_thin_film_exact_lanes(factor, factor * inputs.film_normal_term, inputs.n_o * inputs.cos_o,
                                                        bases.admittance_real, bases.admittance_imaginary) +
                          openpbr_thin_film_exact_lanes(
                              factor * film_ior_squared, factor * inputs.film_normal_term / film_ior_squared,
                              inputs.cos_o / inputs.n_o, admittance_p_real, admittance_p_imaginary));
            }
            else
            {
                values = openpbr_thin_film_tail_lanes(s, tail.amplitude_rho_5.s_real, tail.amplitude_rho_5.s_imaginary,
                                                      tail.numerator_real.low.x, tail.numerator_imaginary.low.x,
                                                      tail.complement_real.low.x, tail.complement_imaginary.low.x) +
                         openpbr_thin_film_tail_lanes(p, tail.amplitude_rho_5.p_real, tail.amplitude_rho_5.p_imaginary,
                                                      tail.numerator_real.low.x, tail.numerator_imaginary.low.x,
                                                      tail.complement_real.low.x, tail.complement_imaginary.low.x);
            }
            // Lane c of the conductor takes channel c's weight, the dielectric every channel's.
            const vec4 weight = vec4(red.low.x, green.low.x, blue.low.x, 0.0f);
            lobe_sums.conductor += weight * values;
            lobe_sums.dielectric += weight * values.w;
            tail.numerator_real = openpbr_thin_film_lobe_queue_next(tail.numerator_real);
            tail.numerator_imaginary = openpbr_thin_film_lobe_queue_next(tail.numerator_imaginary);
            tail.complement_real = openpbr_thin_film_lobe_queue_next(tail.complement_real);
            tail.complement_imaginary = openpbr_thin_film_lobe_queue_next(tail.complement_imaginary);
            red = openpbr_thin_film_lobe_queue_next(red);
            green = openpbr_thin_film_lobe_queue_next(green);
            blue = openpbr_thin_film_lobe_queue_next(blue);
        }
        sums.conductor += lobe_sums.conductor * tail.stacks;
        sums.dielectric += lobe_sums.dielectric * tail.stacks.w;
    }
    if (dielectric)
    {
        pair.dielectric = vec3(sums.dielectric.x, sums.dielectric.y, sums.dielectric.z);
    }
    if (with_conductor)
    {
        pair.conductor = vec3(sums.conductor.x, sums.conductor.y, sums.conductor.z);
    }
    // The sensitivities have negative lobes, so a strongly coloured spectrum can land slightly
    // outside the RGB cube; a reflectance must stay in [0, 1].
    pair.dielectric = openpbr_clamp_finite(pair.dielectric, 0.0f, 1.0f);
    pair.conductor = openpbr_clamp_finite(pair.conductor, 0.0f, 1.0f);
    return pair;
}

#else  // OPENPBR_FILM_FOUR_LANES

// ---- The full model in one lane: the stacks one after another ------------------------------
//
// One film evaluation loops over the stacks that differ in their base (the dielectric, then the
// conductor's three channels), each in scalar and vec2 arithmetic, and sums the six lobes'
// harmonics once per evaluation (openpbr_thin_film_harmonics).

// The closed-form tail m >= 5 of one polarization's series averaged over one spectral lobe:
// g^25 z^5 / (1 - g^15 z), z = rho e^{i delta_j} (the chord of the exponent, see the top).
OPENPBR_FUNC float openpbr_thin_film_lobe_tail(OPENPBR_IN(OpenPBR_ThinFilmPolarization) polarization,
                                               OPENPBR_IN(OpenPBR_ThinFilmLobePhase) phase)
{
    const vec2 round_trip = openpbr_complex_multiply(polarization.rho, phase.phasor);  // z
    const vec2 round_trip_squared = openpbr_complex_multiply(round_trip, round_trip);
    const float damping_squared = phase.damping * phase.damping;
    const float damping_4 = damping_squared * damping_squared;
    const float damping_8 = damping_4 * damping_4;
    const float damping_16 = damping_8 * damping_8;
    // 1 - w z = (1 - rho) + rho (1 - phasor) + (1 - w) z, each part without cancellation.
    const vec2 one_minus_tail_ratio_z = polarization.one_minus_rho +
                                        openpbr_complex_multiply(polarization.rho, phase.one_minus_phasor) +
                                        (1.0f - damping_8 * damping_4 * damping_squared * phase.damping) * round_trip;
    const vec2 round_trip_4 = openpbr_complex_multiply(round_trip_squared, round_trip_squared);
    return damping_16 * damping_8 * phase.damping *
           openpbr_complex_divide(openpbr_complex_multiply(round_trip_4, round_trip), one_minus_tail_ratio_z).x;
}

// Spectral lobe `index` (0 .. 5) of the fit above, selected by index so that the lobe sum is a
// loop whose body exists once in the compiled code (Mesa's NIR inlines every call: written out
// lobe by lobe and channel by channel, one film evaluation compiled to 24 copies of the lobe
// code, and the whole module took 15 s to build on llvmpipe).
struct OpenPBR_ThinFilmSpectralLobe OPENPBR_DIFFERENTIABLE
{
    float nu;     // centre, um^-1
    float sigma;  // deviation, um^-1
    vec3 weight;  // RGB weights
};

OPENPBR_FUNC OpenPBR_ThinFilmSpectralLobe openpbr_thin_film_spectral_lobe(int index)
{
    OpenPBR_ThinFilmSpectralLobe lobe;
    if (index == 0)
    {
        lobe.nu = OPENPBR_THIN_FILM_LOBE0_NU;
        lobe.sigma = OPENPBR_THIN_FILM_LOBE0_SIGMA;
        lobe.weight = OPENPBR_THIN_FILM_LOBE0_WEIGHT;
    }
    else if (index == 1)
    {
        lobe.nu = OPENPBR_THIN_FILM_LOBE1_NU;
        lobe.sigma = OPENPBR_THIN_FILM_LOBE1_SIGMA;
        lobe.weight = OPENPBR_THIN_FILM_LOBE1_WEIGHT;
    }
    else if (index == 2)
    {
        lobe.nu = OPENPBR_THIN_FILM_LOBE2_NU;
        lobe.sigma = OPENPBR_THIN_FILM_LOBE2_SIGMA;
        lobe.weight = OPENPBR_THIN_FILM_LOBE2_WEIGHT;
    }
    else if (index == 3)
    {
        lobe.nu = OPENPBR_THIN_FILM_LOBE3_NU;
        lobe.sigma = OPENPBR_THIN_FILM_LOBE3_SIGMA;
        lobe.weight = OPENPBR_THIN_FILM_LOBE3_WEIGHT;
    }
    else if (index == 4)
    {
        lobe.nu = OPENPBR_THIN_FILM_LOBE4_NU;
        lobe.sigma = OPENPBR_THIN_FILM_LOBE4_SIGMA;
        lobe.weight = OPENPBR_THIN_FILM_LOBE4_WEIGHT;
    }
    else
    {
        lobe.nu = OPENPBR_THIN_FILM_LOBE5_NU;
        lobe.sigma = OPENPBR_THIN_FILM_LOBE5_SIGMA;
        lobe.weight = OPENPBR_THIN_FILM_LOBE5_WEIGHT;
    }
    return lobe;
}

// The film's spectral harmonics at one angle (see the top): H_c(m) for m = 1 .. 4 per RGB
// channel, real and imaginary parts. They depend on the film and the angle only.
struct OpenPBR_ThinFilmHarmonics OPENPBR_DIFFERENTIABLE
{
    vec3 real_1;
    vec3 imaginary_1;
    vec3 real_2;
    vec3 imaginary_2;
    vec3 real_3;
    vec3 imaginary_3;
    vec3 real_4;
    vec3 imaginary_4;
    float largest_tail_damping;  // max_j g_j^25, the damping of the first tail harmonic
};

// Harmonics for a film of optical path difference 2 n_f d cos_f (micrometres): one loop over
// the spectral lobes, six phases in all.
OPENPBR_FUNC OpenPBR_ThinFilmHarmonics openpbr_thin_film_harmonics(float optical_path_difference_um,
                                                                   float optical_path_spread_um)
{
    const float spread_phase_variance = openpbr_thin_film_spread_phase_variance(optical_path_spread_um);
    OpenPBR_ThinFilmHarmonics harmonics;
    harmonics.real_1 = vec3(0.0f);
    harmonics.imaginary_1 = vec3(0.0f);
    harmonics.real_2 = vec3(0.0f);
    harmonics.imaginary_2 = vec3(0.0f);
    harmonics.real_3 = vec3(0.0f);
    harmonics.imaginary_3 = vec3(0.0f);
    harmonics.real_4 = vec3(0.0f);
    harmonics.imaginary_4 = vec3(0.0f);
    harmonics.largest_tail_damping = 0.0f;
    for (int lobe_index = 0; lobe_index < 6; ++lobe_index)
    {
        const OpenPBR_ThinFilmSpectralLobe lobe = openpbr_thin_film_spectral_lobe(lobe_index);
        const OpenPBR_ThinFilmLobePhase phase =
            openpbr_thin_film_lobe_phase(optical_path_difference_um, spread_phase_variance, lobe.nu, lobe.sigma);
        const float damping = phase.damping;
        const float damping_4 = openpbr_square(damping * damping);
        const vec2 phasor_2 = openpbr_complex_multiply(phase.phasor, phase.phasor);
        const vec2 phasor_3 = openpbr_complex_multiply(phasor_2, phase.phasor);
        const vec2 phasor_4 = openpbr_complex_multiply(phasor_2, phasor_2);
        const float damping_16 = openpbr_square(damping_4 * damping_4);
        const vec3 weight_1 = lobe.weight * damping;                            // W g
        const vec3 weight_2 = lobe.weight * damping_4;                          // W g^4
        const vec3 weight_3 = lobe.weight * (damping_4 * damping_4 * damping);  // W g^9
        const vec3 weight_4 = lobe.weight * damping_16;                         // W g^16
        harmonics.real_1 += weight_1 * phase.phasor.x;
        harmonics.imaginary_1 += weight_1 * phase.phasor.y;
        harmonics.real_2 += weight_2 * phasor_2.x;
        harmonics.imaginary_2 += weight_2 * phasor_2.y;
        harmonics.real_3 += weight_3 * phasor_3.x;
        harmonics.imaginary_3 += weight_3 * phasor_3.y;
        harmonics.real_4 += weight_4 * phasor_4.x;
        harmonics.imaginary_4 += weight_4 * phasor_4.y;
        harmonics.largest_tail_damping = max(harmonics.largest_tail_damping, damping_16 * damping_4 * damping_4 * damping);
    }
    return harmonics;
}

// rho^m for m = 1 .. 4 in x .. w, real and imaginary parts: what both harmonic sums weight the
// film's harmonics by.
struct OpenPBR_ThinFilmRhoPowers OPENPBR_DIFFERENTIABLE
{
    vec4 real;
    vec4 imaginary;
};

OPENPBR_FUNC OpenPBR_ThinFilmRhoPowers openpbr_thin_film_rho_powers(vec2 rho)
{
    const vec2 rho_2 = openpbr_complex_multiply(rho, rho);
    const vec2 rho_3 = openpbr_complex_multiply(rho_2, rho);
    const vec2 rho_4 = openpbr_complex_multiply(rho_2, rho_2);
    OpenPBR_ThinFilmRhoPowers powers;
    powers.real = vec4(rho.x, rho_2.x, rho_3.x, rho_4.x);
    powers.imaginary = vec4(rho.y, rho_2.y, rho_3.y, rho_4.y);
    return powers;
}

// mean + 2 A sum_{m=1..4} Re(rho^m H_c(m)) for the three channels.
OPENPBR_FUNC vec3 openpbr_thin_film_harmonic_sum(OPENPBR_IN(OpenPBR_ThinFilmPolarization) polarization,
                                                 OPENPBR_IN(OpenPBR_ThinFilmHarmonics) harmonics)
{
    const OpenPBR_ThinFilmRhoPowers rho = openpbr_thin_film_rho_powers(polarization.rho);
    const vec3 sum = rho.real.x * harmonics.real_1 - rho.imaginary.x * harmonics.imaginary_1 +
                     rho.real.y * harmonics.real_2 - rho.imaginary.y * harmonics.imaginary_2 +
                     rho.real.z * harmonics.real_3 - rho.imaginary.z * harmonics.imaginary_3 +
                     rho.real.w * harmonics.real_4 - rho.imaginary.w * harmonics.imaginary_4;
    return vec3(polarization.mean) + (2.0f * polarization.amplitude) * sum;
}

// One channel's harmonics H_c(m), m = 1 .. 4 in x .. w: what a conductor's stack reads, since
// each of its channels has its own base (summing all three there and keeping one cost twice
// the sum).
struct OpenPBR_ThinFilmChannelHarmonics OPENPBR_DIFFERENTIABLE
{
    vec4 real;
    vec4 imaginary;
};

OPENPBR_FUNC OpenPBR_ThinFilmChannelHarmonics openpbr_thin_film_channel_harmonics(OPENPBR_IN(OpenPBR_ThinFilmHarmonics)
                                                                                      harmonics,
                                                                                  int channel)
{
    OpenPBR_ThinFilmChannelHarmonics result;
    result.real = vec4(openpbr_channel_of(harmonics.real_1, channel), openpbr_channel_of(harmonics.real_2, channel),
                       openpbr_channel_of(harmonics.real_3, channel), openpbr_channel_of(harmonics.real_4, channel));
    result.imaginary =
        vec4(openpbr_channel_of(harmonics.imaginary_1, channel), openpbr_channel_of(harmonics.imaginary_2, channel),
             openpbr_channel_of(harmonics.imaginary_3, channel), openpbr_channel_of(harmonics.imaginary_4, channel));
    return result;
}

// mean + 2 A sum_{m=1..4} Re(rho^m H_c(m)) for one channel.
OPENPBR_FUNC float openpbr_thin_film_channel_harmonic_sum(OPENPBR_IN(OpenPBR_ThinFilmPolarization) polarization,
                                                          OPENPBR_IN(OpenPBR_ThinFilmChannelHarmonics) harmonics)
{
    const OpenPBR_ThinFilmRhoPowers rho = openpbr_thin_film_rho_powers(polarization.rho);
    const float sum = dot(rho.real, harmonics.real) - dot(rho.imaginary, harmonics.imaginary);
    return polarization.mean + 2.0f * polarization.amplitude * sum;
}

// Polarization-averaged reflectance of one stack in all three channels (channel -1, a
// dielectric base), or in one channel 0-2 (a conductor's stack; the result then holds that
// channel's value in every component, and only the caller's channel is meaningful): the
// harmonic sums, plus the tail lobe by lobe where it matters. An
// evanescent film has no fringes: each lobe is evaluated exactly at its centre instead (the
// reflectance is smooth in wavelength there). Both per-lobe cases share one loop, whose body is
// compiled once (llvmpipe unrolls it; a second loop cost 25 % more compile time).
OPENPBR_FUNC vec3 openpbr_thin_film_stack_reflectance(OPENPBR_IN(OpenPBR_ThinFilmStack) stack,
                                                      OPENPBR_IN(OpenPBR_ThinFilmHarmonics) harmonics, int channel)
{
    const bool evanescent = stack.film_is_evanescent;
    vec3 rgb = vec3(0.0f);
    if (!evanescent && channel < 0)
    {
        rgb =
            0.5f * (openpbr_thin_film_harmonic_sum(stack.s, harmonics) + openpbr_thin_film_harmonic_sum(stack.p, harmonics));
    }
    else if (!evanescent)
    {
        const OpenPBR_ThinFilmChannelHarmonics channel_harmonics = openpbr_thin_film_channel_harmonics(harmonics, channel);
        rgb = vec3(0.5f * (openpbr_thin_film_channel_harmonic_sum(stack.s, channel_harmonics) +
                           openpbr_thin_film_channel_harmonic_sum(stack.p, channel_harmonics)));
    }
    if (evanescent ||
        max(stack.s.tail_bound, stack.p.tail_bound) * harmonics.largest_tail_damping > OPENPBR_THIN_FILM_TRUNCATION_ERROR)
    {
        const float spread_phase_variance = openpbr_thin_film_spread_phase_variance(stack.optical_path_spread_um);
        for (int lobe_index = 0; lobe_index < 6; ++lobe_index)
        {
            const OpenPBR_ThinFilmSpectralLobe lobe = openpbr_thin_film_spectral_lobe(lobe_index);
            float lobe_value = 0.0f;
            if (evanescent)
            {
                lobe_value = openpbr_thin_film_evanescent_reflectance(stack, lobe.nu);
            }
            else
            {
                const OpenPBR_ThinFilmLobePhase phase = openpbr_thin_film_lobe_phase(
                    stack.optical_path_difference_um, spread_phase_variance, lobe.nu, lobe.sigma);
                // 0.5 (2 A_s tail_s + 2 A_p tail_p)
                lobe_value = stack.s.amplitude * openpbr_thin_film_lobe_tail(stack.s, phase) +
                             stack.p.amplitude * openpbr_thin_film_lobe_tail(stack.p, phase);
            }
            rgb += lobe.weight * lobe_value;
        }
    }
    return rgb;
}

// One loop over the stacks whose base differs (index 0 the dielectric, 1-3 the conductor's
// channels), so the stack code is compiled once per call site.
OPENPBR_FUNC OpenPBR_ThinFilmBasePair openpbr_thin_film_fresnel_bases(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs,
                                                                      bool with_dielectric, float dielectric_ior,
                                                                      bool with_conductor, vec3 base_n, vec3 base_k)
{
    OpenPBR_ThinFilmBasePair pair = openpbr_thin_film_total_reflection_pair(with_dielectric, with_conductor);
    const float n_b = openpbr_clamp_finite(dielectric_ior, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    const float dielectric_normal_term = openpbr_thin_film_normal_term(n_b, inputs.n_o, inputs.outside_normal_term);
    if (inputs.cos_o <= 0.0f)
    {
        return pair;
    }
    // Total internal reflection at a dielectric base reflects everything (pair.dielectric 1).
    const int first_stack = with_dielectric && dielectric_normal_term > 0.0f ? 0 : 1;
    const int end_stack = with_conductor ? 4 : 1;
    if (with_conductor)
    {
        pair.conductor = vec3(0.0f);
    }
    const OpenPBR_ThinFilmHarmonics harmonics =
        openpbr_thin_film_harmonics(openpbr_thin_film_optical_path_difference(inputs), inputs.optical_path_spread_um);
    // Counted from 0: Slang's reverse mode fails on a loop whose counter starts at a run-time
    // value. At most the dielectric and the three conductor channels.
    OPENPBR_MAX_ITERS(4)
    for (int step = 0; step < end_stack - first_stack; ++step)
    {
        const int stack_index = first_stack + step;
        OpenPBR_ThinFilmBase base;
        base.ior_squared = vec2(n_b * n_b, 0.0f);
        base.normal_term = vec2(sqrt(max(dielectric_normal_term, 0.0f)), 0.0f);
        const int channel = stack_index - 1;
        if (stack_index > 0)
        {
            base = openpbr_thin_film_conductor_base(inputs, openpbr_channel_of(base_n, channel),
                                                    openpbr_channel_of(base_k, channel));
        }
        const OpenPBR_ThinFilmStack stack = openpbr_thin_film_stack(inputs, base.ior_squared, base.normal_term);
        const vec3 rgb = openpbr_thin_film_stack_reflectance(stack, harmonics, channel);
        if (stack_index == 0)
        {
            pair.dielectric = rgb;
        }
        else
        {
            pair.conductor += openpbr_channel_mask(channel) * rgb;
        }
    }
    // The sensitivities have negative lobes, so a strongly coloured spectrum can land slightly
    // outside the RGB cube; a reflectance must stay in [0, 1].
    pair.dielectric = openpbr_clamp_finite(pair.dielectric, 0.0f, 1.0f);
    pair.conductor = openpbr_clamp_finite(pair.conductor, 0.0f, 1.0f);
    return pair;
}

#endif  // OPENPBR_FILM_FOUR_LANES

// ---- Public functions ---------------------------------------------------------------------------

// The full model on one base: a conductor of complex IOR base_n + i base_k per RGB channel, or
// (conductor false) a dielectric of real IOR base_ior. All IORs absolute, thickness in
// micrometres.
OPENPBR_FUNC vec3 openpbr_thin_film_fresnel_full(float cos_theta, float eta_outside, float eta_film, bool conductor,
                                                 float base_ior, vec3 base_n, vec3 base_k, float thickness_um)
{
    const OpenPBR_ThinFilmBasePair pair =
        openpbr_thin_film_fresnel_bases(openpbr_thin_film_inputs(cos_theta, eta_outside, eta_film, thickness_um), !conductor,
                                        base_ior, conductor, base_n, base_k);
    return conductor ? pair.conductor : pair.dielectric;
}

// Film on a dielectric base; all three IORs absolute (e.g. 1.0 air or 1.6 coat, 1.33 film,
// 1.5 base). Thickness in micrometres (OpenPBR's unit). Returns 1 under total internal
// reflection at the base (n_o sin theta >= n_b); an evanescent film (n_o sin theta >= n_f) is
// handled exactly, including light tunnelling through a thin one.
OPENPBR_FUNC vec3 openpbr_thin_film_fresnel_dielectric(float cos_theta, float eta_outside, float eta_film, float eta_base,
                                                       float thickness_um)
{
    return openpbr_thin_film_fresnel_full(cos_theta, eta_outside, eta_film, false, eta_base, vec3(1.0f), vec3(0.0f),
                                          thickness_um);
}

// Film on a conductor of complex IOR base_n + i base_k per RGB channel (absolute; e.g. from
// openpbr_gulbrandsen_n / _k).
OPENPBR_FUNC vec3 openpbr_thin_film_fresnel_conductor(float cos_theta, float eta_outside, float eta_film, vec3 base_n,
                                                      vec3 base_k, float thickness_um)
{
    return openpbr_thin_film_fresnel_full(cos_theta, eta_outside, eta_film, true, 1.0f, base_n, base_k, thickness_um);
}

// Fast model, one polarization: every harmonic m damped by g^m instead of the Gaussian's
// g^(m^2), which sums in closed form: mean + 2 A Re(g z / (1 - g z)).
OPENPBR_FUNC float openpbr_thin_film_damped_airy(OPENPBR_IN(OpenPBR_ThinFilmPolarization) polarization,
                                                 OPENPBR_IN(OpenPBR_ThinFilmLobePhase) phase)
{
    const vec2 round_trip = openpbr_complex_multiply(polarization.rho, phase.phasor);
    const float damping = phase.damping;
    // 1 - g z = (1 - rho) + rho (1 - phasor) + (1 - g) z, as in the full series' tail.
    const vec2 one_minus_damped_round_trip = polarization.one_minus_rho +
                                             openpbr_complex_multiply(polarization.rho, phase.one_minus_phasor) +
                                             (1.0f - damping) * round_trip;
    return polarization.mean +
           2.0f * polarization.amplitude * damping * openpbr_complex_divide(round_trip, one_minus_damped_round_trip).x;
}

// Fast model for one channel: the stack at the channel's single-Gaussian centre nu, with the
// damping g of that Gaussian applied as g^m to harmonic m.
OPENPBR_FUNC float openpbr_thin_film_fast_channel(OPENPBR_IN(OpenPBR_ThinFilmStack) stack, float nu, float sigma)
{
    if (stack.film_is_evanescent)
    {
        return openpbr_thin_film_evanescent_reflectance(stack, nu);
    }
    const OpenPBR_ThinFilmLobePhase phase = openpbr_thin_film_lobe_phase(
        stack.optical_path_difference_um, openpbr_thin_film_spread_phase_variance(stack.optical_path_spread_um), nu, sigma);
    return 0.5f * (openpbr_thin_film_damped_airy(stack.s, phase) + openpbr_thin_film_damped_airy(stack.p, phase));
}

// The fast model on either base or both (arguments and result as openpbr_thin_film_fresnel_bases).
OPENPBR_FUNC OpenPBR_ThinFilmBasePair openpbr_thin_film_fast_bases(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs,
                                                                   bool with_dielectric, float dielectric_ior,
                                                                   bool with_conductor, vec3 base_n, vec3 base_k)
{
    OpenPBR_ThinFilmBasePair pair = openpbr_thin_film_total_reflection_pair(with_dielectric, with_conductor);
    if (inputs.cos_o <= 0.0f)
    {
        return pair;
    }
    const vec3 nu = OPENPBR_THIN_FILM_FAST_NU;
    const vec3 sigma = OPENPBR_THIN_FILM_FAST_SIGMA;
    const float n_b = openpbr_clamp_finite(dielectric_ior, OPENPBR_THIN_FILM_MIN_IOR, OPENPBR_THIN_FILM_MAX_IOR);
    const float base_normal_term = openpbr_thin_film_normal_term(n_b, inputs.n_o, inputs.outside_normal_term);
    // Total internal reflection at a dielectric base reflects everything (pair.dielectric 1).
    if (with_dielectric && base_normal_term > 0.0f)
    {
        const OpenPBR_ThinFilmStack stack =
            openpbr_thin_film_stack(inputs, vec2(n_b * n_b, 0.0f), vec2(sqrt(base_normal_term), 0.0f));
        pair.dielectric = openpbr_clamp_finite(vec3(openpbr_thin_film_fast_channel(stack, nu.x, sigma.x),
                                                    openpbr_thin_film_fast_channel(stack, nu.y, sigma.y),
                                                    openpbr_thin_film_fast_channel(stack, nu.z, sigma.z)),
                                               0.0f, 1.0f);
    }
    if (with_conductor)
    {
        pair.conductor = openpbr_clamp_finite(
            vec3(
                openpbr_thin_film_fast_channel(openpbr_thin_film_conductor_stack(inputs, base_n.x, base_k.x), nu.x, sigma.x),
                openpbr_thin_film_fast_channel(openpbr_thin_film_conductor_stack(inputs, base_n.y, base_k.y), nu.y, sigma.y),
                openpbr_thin_film_fast_channel(openpbr_thin_film_conductor_stack(inputs, base_n.z, base_k.z), nu.z,
                                               sigma.z)),
            0.0f, 1.0f);
    }
    return pair;
}

OPENPBR_FUNC vec3 openpbr_thin_film_fresnel_dielectric_fast(float cos_theta, float eta_outside, float eta_film,
                                                            float eta_base, float thickness_um)
{
    return openpbr_thin_film_fast_bases(openpbr_thin_film_inputs(cos_theta, eta_outside, eta_film, thickness_um), true,
                                        eta_base, false, vec3(1.0f), vec3(0.0f))
        .dielectric;
}

OPENPBR_FUNC vec3 openpbr_thin_film_fresnel_conductor_fast(float cos_theta, float eta_outside, float eta_film, vec3 base_n,
                                                           vec3 base_k, float thickness_um)
{
    return openpbr_thin_film_fast_bases(openpbr_thin_film_inputs(cos_theta, eta_outside, eta_film, thickness_um), false,
                                        1.0f, true, base_n, base_k)
        .conductor;
}

// ---- Model choice ----------------------------------------------------------------------------

// OPENPBR_THIN_FILM_MODEL picks what the Fresnel factors of filmed lobes evaluate, e.g.
// -DOPENPBR_THIN_FILM_MODEL=OPENPBR_THIN_FILM_MODEL_FAST. Default FULL (the spectral model);
// FAST is the three-Gaussian approximation above (docs/accuracy-vs-time.md has its error and
// time).
#define OPENPBR_THIN_FILM_MODEL_FULL 0
#define OPENPBR_THIN_FILM_MODEL_FAST 1
#ifndef OPENPBR_THIN_FILM_MODEL
#define OPENPBR_THIN_FILM_MODEL OPENPBR_THIN_FILM_MODEL_FULL
#endif

// The chosen model on either base or both (arguments and result as
// openpbr_thin_film_fresnel_bases): every lobe evaluates its film through this, the base
// pair's evaluation included, so sample, eval and pdf read the same model.
OPENPBR_FUNC OpenPBR_ThinFilmBasePair openpbr_thin_film_model_bases(OPENPBR_IN(OpenPBR_ThinFilmInputs) inputs,
                                                                    bool with_dielectric, float dielectric_ior,
                                                                    bool with_conductor, vec3 base_n, vec3 base_k)
{
#if OPENPBR_THIN_FILM_MODEL == OPENPBR_THIN_FILM_MODEL_FAST
    return openpbr_thin_film_fast_bases(inputs, with_dielectric, dielectric_ior, with_conductor, base_n, base_k);
#else
    return openpbr_thin_film_fresnel_bases(inputs, with_dielectric, dielectric_ior, with_conductor, base_n, base_k);
#endif
}

// The chosen model on one base (arguments as openpbr_thin_film_fresnel_full).
OPENPBR_FUNC vec3 openpbr_thin_film_fresnel_model(float cos_theta, float eta_outside, float eta_film, bool conductor,
                                                  float base_ior, vec3 base_n, vec3 base_k, float thickness_um)
{
#if OPENPBR_THIN_FILM_MODEL == OPENPBR_THIN_FILM_MODEL_FAST
    return conductor
               ? openpbr_thin_film_fresnel_conductor_fast(cos_theta, eta_outside, eta_film, base_n, base_k, thickness_um)
               : openpbr_thin_film_fresnel_dielectric_fast(cos_theta, eta_outside, eta_film, base_ior, thickness_um);
#else
    return openpbr_thin_film_fresnel_full(cos_theta, eta_outside, eta_film, conductor, base_ior, base_n, base_k,
                                          thickness_um);
#endif
}

// ---- Metal IOR from artist colours ------------------------------------------------------------

// Gulbrandsen 2014, "Artist Friendly Metallic Fresnel" (JCGT 3(4)): the complex IOR n + i k
// (relative to a medium of index 1) whose normal-incidence reflectance is r, with the edge tint
// g choosing n between n_max (g = 0, k = 0) and n_min (g = 1):
//   n = g (1 - r)/(1 + r) + (1 - g)(1 + sqrt r)/(1 - sqrt r),
//   k = sqrt((r (n + 1)^2 - (n - 1)^2) / (1 - r)).
// For OpenPBR's metal, r = base_weight * base_color (F0) and g = specular_color are used. That
// is an approximation: OpenPBR's specular_color multiplies the F82-tint curve at 82 degrees
// (Hoffman / Kutz et al.), while Gulbrandsen's g shapes the edge of the exact conductor
// Fresnel curve, so with a zero-thickness film the result matches F0 exactly at normal
// incidence but only approximately towards grazing. r is clamped to [0, 0.9999] and g to
// [0, 1]; n is clamped to the film model's IOR range [OPENPBR_THIN_FILM_MIN_IOR,
// OPENPBR_THIN_FILM_MAX_IOR] before k is derived from it, so the pair (n, k) the film sees
// still reflects exactly r at normal incidence (n_min -> 0 and n_max -> infinity as r -> 1:
// clamping n alone afterwards turned a white metal, r = 1, into a 98 % reflector that lost
// 2 % in the white furnace).
OPENPBR_FUNC vec3 openpbr_gulbrandsen_n(vec3 r, vec3 g)
{
    const vec3 reflectivity = openpbr_clamp_finite(r, 0.0f, 0.9999f);
    const vec3 edge_tint = openpbr_clamp_finite(g, 0.0f, 1.0f);
    const vec3 sqrt_r = sqrt(reflectivity);
    const vec3 n_min = (vec3(1.0f) - reflectivity) / (vec3(1.0f) + reflectivity);
    const vec3 n_max = (vec3(1.0f) + sqrt_r) / (vec3(1.0f) - sqrt_r);
    return clamp(edge_tint * n_min + (vec3(1.0f) - edge_tint) * n_max, vec3(OPENPBR_THIN_FILM_MIN_IOR),
                 vec3(OPENPBR_THIN_FILM_MAX_IOR));
}

OPENPBR_FUNC vec3 openpbr_gulbrandsen_k(vec3 r, vec3 n)
{
    const vec3 reflectivity = openpbr_clamp_finite(r, 0.0f, 0.9999f);
    const vec3 k_squared =
        (reflectivity * openpbr_square(n + vec3(1.0f)) - openpbr_square(n - vec3(1.0f))) / (vec3(1.0f) - reflectivity);
    return sqrt(max(k_squared, vec3(0.0f)));
}

OPENPBR_NAMESPACE_END

#endif
