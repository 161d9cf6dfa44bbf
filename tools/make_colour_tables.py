#!/usr/bin/env python3
"""Derives every colour-dependent number of the project from its definition, once.

The definitions are written here and nowhere else:
  * the CIE 1931 2-degree standard observer: the 5 nm table of CIE 015 (ISO/CIE 11664-1),
    380-780 nm, for the spectral locus; and the multi-lobe analytic fit of Wyman, Sloan &
    Shirley 2013 ("Simple Analytic Approximations to the CIE XYZ Color Matching Functions",
    JCGT 2(2)) for the thin film's spectral sensitivities, which integrate Gaussians and need a
    smooth function (tests/bsdf/test_thin_film.cpp's spectral reference uses the same fit);
  * the primaries and white points of the RGB spaces (chromaticities xy): Rec.709 / sRGB
    (ITU-R BT.709, IEC 61966-2-1), ACES AP1 with the ACES white (SMPTE ST 2065-1, ACEScg
    S-2014-004), Display P3 (P3 primaries, D65), Adobe RGB (1998);
  * the transfer functions: the sRGB curve of IEC 61966-2-1 and pure powers (1.8, 2.2; Adobe
    RGB as the ASWF Color Interop Forum's "Gamma 2.2 Encoded AdobeRGB", MaterialX's adobergb);
  * the Bradford cone response matrix (Lam 1985) for the chromatic adaptation between white
    points (ACES white <-> D65), as the ACES transforms and OpenColorIO's ACES configs adapt.

From them it writes (all committed; `--check` says whether they are up to date):
  slang/generated/openpbr_working_space_constants.h
      the BSDF's colour-dependent constants for each working space (slang/openpbr_working_space.h
      picks one): luminance weights (the Y row of RGB -> XYZ), the dominant wavelengths of the
      primaries (the channels' wavelengths for dispersion), the thin film's spectral lobes
      (six shared Gaussians over the wavenumber with per-channel weights refit to the space's
      sensitivities) and the fast film model's one Gaussian per channel;
  host/scene/colour_space_table.h and viewer/src/colour_spaces.mjs
      the MaterialX colour spaces the loaders read (name, transfer function, matrix into each
      working space) and the working space -> display (linear Rec.709) matrices, the same
      numbers for C++ and JavaScript (17 significant digits: every double exactly);
  viewer/display.wgsl (the block between its "generated" markers)
      the working space -> Rec.709 matrix of the library's default working space;
  tests/data/colour_conversions.json
      conversions of sample values, computed here in double precision and rounded to float32,
      that the C++ and the JavaScript tests both reproduce (the two loaders agree through them);
  tests/data/colour_spaces/<space>.mtlx
      one document per MaterialX colour space holding the same two colours (given in linear
      Rec.709), which the loader must read to the same working values.

Usage: tools/make_colour_tables.py [--check] [ROOT]  (ROOT: the repository, default the parent
of tools/). --check writes nothing and exits 1 naming every output that differs from what this
script would write. Pure Python 3 (no packages): about 2 s of CPU.
"""
import json
import math
import pathlib
import re
import struct
import sys

# ---- Definitions ------------------------------------------------------------------------------

# CIE 1931 2-degree colour matching functions, 380..780 nm every 5 nm (CIE 015, ISO/CIE 11664-1).
CIE_START_NM = 380
CIE_STEP_NM = 5
CIE_X = [
    0.001368, 0.002236, 0.004243, 0.00765, 0.01431, 0.02319, 0.04351, 0.07763, 0.13438, 0.21477, 0.2839, 0.3285,
    0.34828, 0.34806, 0.3362, 0.3187, 0.2908, 0.2511, 0.19536, 0.1421, 0.09564, 0.05795, 0.03201, 0.0147, 0.0049,
    0.0024, 0.0093, 0.0291, 0.06327, 0.1096, 0.1655, 0.22575, 0.2904, 0.3597, 0.43345, 0.51205, 0.5945, 0.6784,
    0.7621, 0.8425, 0.9163, 0.9786, 1.0263, 1.0567, 1.0622, 1.0456, 1.0026, 0.9384, 0.85445, 0.7514, 0.6424,
    0.5419, 0.4479, 0.3608, 0.2835, 0.2187, 0.1649, 0.1212, 0.0874, 0.0636, 0.04677, 0.0329, 0.0227, 0.01584,
    0.01135916, 0.008110916, 0.005790346, 0.004109457, 0.002899327, 0.00204919, 0.001439971, 0.0009999493,
    0.0006900786, 0.0004760213, 0.0003323011, 0.0002348261, 0.0001661505, 0.000117413, 8.307527e-05,
    5.870652e-05, 4.150994e-05,
]
CIE_Y = [
    3.9e-05, 6.4e-05, 0.00012, 0.000217, 0.000396, 0.00064, 0.00121, 0.00218, 0.004, 0.0073, 0.0116, 0.01684,
    0.023, 0.0298, 0.038, 0.048, 0.06, 0.0739, 0.09098, 0.1126, 0.13902, 0.1693, 0.20802, 0.2586, 0.323, 0.4073,
    0.503, 0.6082, 0.71, 0.7932, 0.862, 0.91485, 0.954, 0.9803, 0.99495, 1.0, 0.995, 0.9786, 0.952, 0.9154, 0.87,
    0.8163, 0.757, 0.6949, 0.631, 0.5668, 0.503, 0.4412, 0.381, 0.321, 0.265, 0.217, 0.175, 0.1382, 0.107,
    0.0816, 0.061, 0.04458, 0.032, 0.0232, 0.017, 0.01192, 0.00821, 0.005723, 0.004102, 0.002929, 0.002091,
    0.001484, 0.001047, 0.00074, 0.00052, 0.0003611, 0.0002492, 0.0001719, 0.00012, 8.48e-05, 6e-05, 4.24e-05,
    3e-05, 2.12e-05, 1.499e-05,
]
CIE_Z = [
    0.00645, 0.01055, 0.02005, 0.03621, 0.06785, 0.1102, 0.2074, 0.3713, 0.6456, 1.03905, 1.3856, 1.62296,
    1.74706, 1.7826, 1.77211, 1.7441, 1.6692, 1.5281, 1.28764, 1.0419, 0.81295, 0.6162, 0.46518, 0.3533, 0.272,
    0.2123, 0.1582, 0.1117, 0.07825, 0.05725, 0.04216, 0.02984, 0.0203, 0.0134, 0.00875, 0.00575, 0.0039, 0.00275,
    0.0021, 0.0018, 0.00165, 0.0014, 0.0011, 0.001, 0.0008, 0.0006, 0.00034, 0.00024, 0.00019, 0.0001, 5e-05,
    3e-05, 2e-05, 1e-05,
] + [0.0] * 27


def wyman_xyz(wavelength_nm):
    """CIE 1931 2-degree CMFs, the multi-lobe fit of Wyman, Sloan & Shirley 2013 (nm)."""
    def lobe(mean, sigma_below, sigma_above):
        t = (wavelength_nm - mean) / (sigma_below if wavelength_nm < mean else sigma_above)
        return math.exp(-0.5 * t * t)
    return (1.056 * lobe(599.8, 37.9, 31.0) + 0.362 * lobe(442.0, 16.0, 26.7) - 0.065 * lobe(501.1, 20.4, 26.2),
            0.821 * lobe(568.8, 46.9, 40.5) + 0.286 * lobe(530.9, 16.3, 31.1),
            1.217 * lobe(437.0, 11.8, 36.0) + 0.681 * lobe(459.0, 26.0, 13.8))


D65 = (0.3127, 0.3290)
ACES_WHITE = (0.32168, 0.33767)
REC709_PRIMARIES = ((0.64, 0.33), (0.30, 0.60), (0.15, 0.06))
AP1_PRIMARIES = ((0.713, 0.293), (0.165, 0.830), (0.128, 0.044))
P3_PRIMARIES = ((0.680, 0.320), (0.265, 0.690), (0.150, 0.060))
ADOBE_PRIMARIES = ((0.64, 0.33), (0.21, 0.71), (0.15, 0.06))

# Bradford cone response (Lam 1985): XYZ -> the sharpened cone space of the adaptation.
BRADFORD = ((0.8951, 0.2664, -0.1614), (-0.7502, 1.7135, 0.0367), (0.0389, -0.0685, 1.0296))

# The working spaces, in the order of their OPENPBR_WORKING_SPACE values
# (slang/openpbr_working_space.h): OPENPBR_WORKING_SPACE_<MACRO> = index.
WORKING_SPACES = [
    {"name": "lin_rec709", "macro": "LIN_REC709", "primaries": REC709_PRIMARIES, "white": D65},
    {"name": "acescg", "macro": "ACESCG", "primaries": AP1_PRIMARIES, "white": ACES_WHITE},
]

# The colour spaces of MaterialX documents (MaterialX 1.39 "Color Spaces and Color Management
# Systems"), then their other spellings: MaterialX's legacy names and the ASWF Color Interop
# Forum identifiers MaterialX 1.39 maps to them. transfer: "linear", "srgb" (IEC 61966-2-1) or
# "gamma" (a pure power, exponent).
COLOUR_SPACES = [
    ("acescg", AP1_PRIMARIES, ACES_WHITE, "linear", 1.0),
    ("g22_ap1", AP1_PRIMARIES, ACES_WHITE, "gamma", 2.2),
    ("g18_ap1", AP1_PRIMARIES, ACES_WHITE, "gamma", 1.8),
    ("lin_rec709", REC709_PRIMARIES, D65, "linear", 1.0),
    ("g22_rec709", REC709_PRIMARIES, D65, "gamma", 2.2),
    ("g18_rec709", REC709_PRIMARIES, D65, "gamma", 1.8),
    ("srgb_texture", REC709_PRIMARIES, D65, "srgb", 2.4),
    ("lin_displayp3", P3_PRIMARIES, D65, "linear", 1.0),
    ("srgb_displayp3", P3_PRIMARIES, D65, "srgb", 2.4),
    ("lin_adobergb", ADOBE_PRIMARIES, D65, "linear", 1.0),
    ("adobergb", ADOBE_PRIMARIES, D65, "gamma", 2.2),
]
ALIASES = [
    ("lin_ap1", "acescg"),
    ("gamma18", "g18_rec709"),
    ("gamma22", "g22_rec709"),
    ("lin_ap1_scene", "acescg"),
    ("g22_ap1_scene", "g22_ap1"),
    ("lin_rec709_scene", "lin_rec709"),
    ("g22_rec709_scene", "g22_rec709"),
    ("g18_rec709_scene", "g18_rec709"),
    ("srgb_rec709_scene", "srgb_texture"),
    ("lin_p3d65_scene", "lin_displayp3"),
    ("srgb_p3d65_scene", "srgb_displayp3"),
    ("lin_adobergb_scene", "lin_adobergb"),
    ("g22_adobergb_scene", "adobergb"),
]
# What a document that names no colour space is in: the OpenPBR specification ("Metadata"):
# "If unspecified, following MaterialX, by default this color space is assumed to be ACEScg".
DEFAULT_DOCUMENT_SPACE = "acescg"
# The display: Rec.709 primaries (the sRGB display's), linear.
DISPLAY_SPACE = "lin_rec709"

# The thin film's six spectral lobes over the wavenumber nu (um^-1): centres and standard
# deviations, fitted once (with the weights) to the Rec.709 sensitivities over 1/0.78 .. 1/0.38
# um^-1. They stay fixed; each working space's per-channel weights are refit below.
FILM_LOBES = [
    (1.6299326, 0.0654941), (1.7149580, 0.0951775), (1.8647213, 0.0922642),
    (2.0936911, 0.1170459), (2.2295382, 0.0473544), (2.2315741, 0.0916354),
]
FILM_GRID_POINTS = 2001  # samples of the fits over the wavenumber range
FILM_RIDGE = 1e-4        # ridge term of the weight fit, against cancelling lobe pairs

# ---- Linear algebra (3 x 3, row-major tuples) ----------------------------------------------------


def multiply(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def apply(m, v):
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


def inverse(m):
    (a, b, c), (d, e, f), (g, h, i) = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return ((((e * i - f * h) / det), ((c * h - b * i) / det), ((b * f - c * e) / det)),
            (((f * g - d * i) / det), ((a * i - c * g) / det), ((c * d - a * f) / det)),
            (((d * h - e * g) / det), ((b * g - a * h) / det), ((a * e - b * d) / det)))


def xy_to_xyz(xy):
    return (xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1])


def rgb_to_xyz(primaries, white):
    """The RGB -> XYZ matrix of primaries and white (SMPTE RP 177): white (1, 1, 1) -> Y = 1."""
    columns = [xy_to_xyz(p) for p in primaries]
    p = tuple(tuple(columns[c][r] for c in range(3)) for r in range(3))
    scale = apply(inverse(p), xy_to_xyz(white))
    return tuple(tuple(p[r][c] * scale[c] for c in range(3)) for r in range(3))


def bradford(source_white, target_white):
    """Bradford adaptation XYZ (source white) -> XYZ (target white)."""
    source = apply(BRADFORD, xy_to_xyz(source_white))
    target = apply(BRADFORD, xy_to_xyz(target_white))
    scale = tuple(tuple((target[i] / source[i]) if i == j else 0.0 for j in range(3)) for i in range(3))
    return multiply(inverse(BRADFORD), multiply(scale, BRADFORD))


IDENTITY = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def conversion(source_primaries, source_white, target_primaries, target_white):
    """Linear RGB (source) -> linear RGB (target), adapting the white; exactly the identity
    between identical spaces, so a value in the working space passes unchanged."""
    if source_primaries == target_primaries and source_white == target_white:
        return IDENTITY
    adapt = IDENTITY if source_white == target_white else bradford(source_white, target_white)
    return multiply(inverse(rgb_to_xyz(target_primaries, target_white)),
                    multiply(adapt, rgb_to_xyz(source_primaries, source_white)))


# ---- Transfer functions (decode: encoded file value -> linear), odd-extended below 0 -----------


def decode(transfer, exponent, value):
    magnitude = abs(value)
    if transfer == "linear":
        linear = magnitude
    elif transfer == "srgb":
        linear = magnitude / 12.92 if magnitude <= 0.04045 else ((magnitude + 0.055) / 1.055) ** 2.4
    else:
        linear = magnitude ** exponent
    return -linear if value < 0.0 else linear


# ---- BSDF constants -----------------------------------------------------------------------------


def dominant_wavelength(primary, white):
    """Where the ray from the white through the primary leaves the spectral locus (the first
    crossing from short wavelengths; the locus linearly interpolated between table samples)."""
    direction = (primary[0] - white[0], primary[1] - white[1])

    def side(index):
        x, y, z = CIE_X[index], CIE_Y[index], CIE_Z[index]
        total = x + y + z
        point = (x / total - white[0], y / total - white[1])
        return direction[0] * point[1] - direction[1] * point[0], point

    previous, _ = side(0)
    for index in range(1, len(CIE_X)):
        current, point = side(index)
        ahead = point[0] * direction[0] + point[1] * direction[1] > 0.0
        if ahead and (previous > 0.0) != (current > 0.0):
            fraction = previous / (previous - current)
            return CIE_START_NM + CIE_STEP_NM * (index - 1 + fraction)
        previous = current
    raise ValueError(f"no dominant wavelength for primary {primary}")


def film_grid():
    low, high = 1.0 / 0.78, 1.0 / 0.38
    step = (high - low) / (FILM_GRID_POINTS - 1)
    return [low + step * k for k in range(FILM_GRID_POINTS)], step


def normal_pdf(x, mean, sigma):
    return math.exp(-0.5 * ((x - mean) / sigma) ** 2) / (sigma * math.sqrt(2.0 * math.pi))


def film_sensitivities(xyz_to_rgb):
    """Each channel's sensitivity as a unit-area density over the wavenumber nu (um^-1): the RGB
    of the CMFs at lambda = 1/nu times |d lambda / d nu|, so a flat spectrum of 1 gives 1."""
    grid, step = film_grid()
    channels = [[], [], []]
    for nu in grid:
        wavelength = 1000.0 / nu
        rgb = apply(xyz_to_rgb, wyman_xyz(wavelength))
        for c in range(3):
            channels[c].append(rgb[c] * wavelength * wavelength)
    for c in range(3):
        area = sum(channels[c]) * step
        channels[c] = [v / area for v in channels[c]]
    return channels


def solve(matrix, rhs):
    """Gaussian elimination with partial pivoting (small dense systems)."""
    n = len(rhs)
    rows = [list(matrix[i]) + [rhs[i]] for i in range(n)]
    for i in range(n):
        pivot = max(range(i, n), key=lambda r: abs(rows[r][i]))
        rows[i], rows[pivot] = rows[pivot], rows[i]
        for r in range(n):
            if r != i:
                factor = rows[r][i] / rows[i][i]
                for c in range(i, n + 1):
                    rows[r][c] -= factor * rows[i][c]
    return [rows[i][n] / rows[i][i] for i in range(n)]


def fit_film_weights(target):
    """Weights W_j of sum_j W_j N(nu; nu_j, sigma_j) for one channel: least squares against the
    target with a ridge term, the weights constrained to sum to 1 (Lagrange multiplier)."""
    grid, step = film_grid()
    basis = [[normal_pdf(nu, mean, sigma) for (mean, sigma) in FILM_LOBES] for nu in grid]
    n = len(FILM_LOBES)
    gram = [[sum(row[i] * row[j] for row in basis) * step + (FILM_RIDGE if i == j else 0.0) for j in range(n)]
            for i in range(n)]
    projection = [sum(row[i] * t for row, t in zip(basis, target)) * step for i in range(n)]
    system = [gram[i] + [1.0] for i in range(n)] + [[1.0] * n + [0.0]]
    weights = solve(system, projection + [1.0])[:n]
    l1_error = sum(abs(sum(w * b for w, b in zip(weights, row)) - t) for row, t in zip(basis, target)) * step
    return weights, l1_error


def fit_one_gaussian(target):
    """The fast film model's Gaussian for one channel: least squares of a * N(nu; mean, sigma)
    against the target (Levenberg-Marquardt from the target's centroid); the model then uses
    the unit-area Gaussian (a flat spectrum stays flat)."""
    grid, step = film_grid()
    mean = sum(nu * t for nu, t in zip(grid, target)) * step
    params = [1.0, mean, 0.08]
    damping = 1e-3

    def residuals(p):
        return [p[0] * normal_pdf(nu, p[1], p[2]) - t for nu, t in zip(grid, target)]

    cost = sum(r * r for r in residuals(params))
    for _ in range(200):
        amplitude, centre, sigma = params
        jacobian = []
        for nu in grid:
            g = normal_pdf(nu, centre, sigma)
            u = (nu - centre) / sigma
            jacobian.append((g, amplitude * g * u / sigma, amplitude * g * (u * u - 1.0) / sigma))
        residual = residuals(params)
        normal = [[sum(row[i] * row[j] for row in jacobian) for j in range(3)] for i in range(3)]
        gradient = [sum(row[i] * r for row, r in zip(jacobian, residual)) for i in range(3)]
        for i in range(3):
            normal[i][i] *= 1.0 + damping
        delta = solve(normal, [-g for g in gradient])
        trial = [p + d for p, d in zip(params, delta)]
        trial_cost = sum(r * r for r in residuals(trial)) if trial[2] > 0.0 else math.inf
        if trial_cost < cost:
            converged = cost - trial_cost < 1e-15 * cost
            params, cost, damping = trial, trial_cost, damping * 0.3
            if converged:
                break
        else:
            damping *= 10.0
    return params[1], params[2]


def working_space_constants(space):
    to_xyz = rgb_to_xyz(space["primaries"], space["white"])
    sensitivities = film_sensitivities(inverse(to_xyz))
    weights, errors = zip(*(fit_film_weights(channel) for channel in sensitivities))
    fast = [fit_one_gaussian(channel) for channel in sensitivities]
    return {
        "luminance": to_xyz[1],
        "wavelengths": [dominant_wavelength(p, space["white"]) for p in space["primaries"]],
        "film_weights": [[weights[c][j] for c in range(3)] for j in range(len(FILM_LOBES))],
        "film_errors": errors,
        "fast_nu": [f[0] for f in fast],
        "fast_sigma": [f[1] for f in fast],
    }


# ---- Writers ------------------------------------------------------------------------------------

GENERATED_NOTE = "Generated by tools/make_colour_tables.py from the definitions written there; do not edit."


def c_float(value, digits=9):
    text = f"{value:.{digits}g}"
    if "." not in text and "e" not in text:
        text += ".0"
    return text + "f"


def c_vec3(values, digits=9):
    return "vec3(" + ", ".join(c_float(v, digits) for v in values) + ")"


def exact(value):
    """Shortest text that reads back as the same double, in C++ and JavaScript alike."""
    text = repr(float(value))
    return "0.0" if text == "-0.0" else text


def slang_header(constants):
    lines = [
        f"// {GENERATED_NOTE}",
        "// The BSDF's colour-dependent constants for each working space; slang/openpbr_working_space.h",
        "// includes this after setting OPENPBR_WORKING_SPACE (docs/colour.md says how each is derived).",
        "//   OPENPBR_WORKING_SPACE_LUMINANCE_WEIGHTS       the Y row of the space's RGB -> XYZ (sum 1)",
        "//   OPENPBR_WORKING_SPACE_DOMINANT_WAVELENGTHS_NM the dominant wavelengths of its primaries",
        "//       (CIE 1931 spectral locus, seen from its white point)",
        "//   OPENPBR_THIN_FILM_LOBE<j>_NU / _SIGMA / _WEIGHT six Gaussian lobes over the wavenumber (um^-1)",
        "//       shared by every space, with per-channel weights (summing to 1) fit to the space's RGB",
        "//       sensitivities (slang/math/openpbr_thin_film.h, \"Spectral lobes\")",
        "//   OPENPBR_THIN_FILM_FAST_NU / _SIGMA            the fast film model's one Gaussian per channel",
        "#ifndef OPENPBR_WORKING_SPACE_CONSTANTS_H",
        "#define OPENPBR_WORKING_SPACE_CONSTANTS_H",
        "",
    ]
    for index, (space, values) in enumerate(zip(WORKING_SPACES, constants)):
        keyword = "#if" if index == 0 else "#elif"
        lines.append(f"{keyword} OPENPBR_WORKING_SPACE == OPENPBR_WORKING_SPACE_{space['macro']}")
        errors = ", ".join(f"{e:.3f}" for e in values["film_errors"])
        lines.append(f"// {space['name']}: film weight fit L1 error (R, G, B) {errors} of the unit-area sensitivities")
        lines.append(f"#define OPENPBR_WORKING_SPACE_LUMINANCE_WEIGHTS {c_vec3(values['luminance'], 7)}")
        lines.append(f"#define OPENPBR_WORKING_SPACE_DOMINANT_WAVELENGTHS_NM {c_vec3(values['wavelengths'], 4)}")
        for j, (mean, sigma) in enumerate(FILM_LOBES):
            lines.append(f"#define OPENPBR_THIN_FILM_LOBE{j}_NU {c_float(mean, 8)}")
            lines.append(f"#define OPENPBR_THIN_FILM_LOBE{j}_SIGMA {c_float(sigma, 7)}")
            lines.append(f"#define OPENPBR_THIN_FILM_LOBE{j}_WEIGHT {c_vec3(values['film_weights'][j], 7)}")
        lines.append(f"#define OPENPBR_THIN_FILM_FAST_NU {c_vec3(values['fast_nu'], 7)}")
        lines.append(f"#define OPENPBR_THIN_FILM_FAST_SIGMA {c_vec3(values['fast_sigma'], 6)}")
    lines += [
        "#else",
        "#error \"OPENPBR_WORKING_SPACE must be OPENPBR_WORKING_SPACE_LIN_REC709 or OPENPBR_WORKING_SPACE_ACESCG\"",
        "#endif",
        "",
        "#endif",
        "",
    ]
    return "\n".join(lines)


def file_space_rows():
    """(name, canonical, transfer, exponent, [matrix into each working space]) per name."""
    definitions = {name: (primaries, white, transfer, exponent)
                   for name, primaries, white, transfer, exponent in COLOUR_SPACES}
    rows = []
    for name, canonical in [(n, n) for n, *_ in COLOUR_SPACES] + ALIASES:
        primaries, white, transfer, exponent = definitions[canonical]
        matrices = [conversion(primaries, white, space["primaries"], space["white"]) for space in WORKING_SPACES]
        rows.append((name, canonical, transfer, exponent, matrices))
    return rows


def display_matrices():
    display = next(row for row in COLOUR_SPACES if row[0] == DISPLAY_SPACE)
    return [conversion(space["primaries"], space["white"], display[1], display[2]) for space in WORKING_SPACES]


def cpp_matrix(m):
    return "{" + ", ".join(exact(v) for row in m for v in row) + "}"


def cpp_table():
    lines = [
        f"// {GENERATED_NOTE}",
        "// The MaterialX colour spaces the loader converts from (host/scene/colour_spaces.h reads this",
        "// table; viewer/src/colour_spaces.mjs holds the same numbers for the viewer's loader): per name,",
        "// the transfer function and the linear RGB matrix into each working space (index: the",
        "// OPENPBR_WORKING_SPACE value, slang/openpbr_working_space.h), row-major, white adapted by",
        "// Bradford where the white points differ; then working space -> display (linear Rec.709).",
        "#pragma once",
        "",
        "#include <array>",
        "#include <string_view>",
        "",
        "// The generator's layout, one row per name (clang-format would rewrap it).",
        "// clang-format off",
        "namespace openpbr::host::colour_table {",
        "",
        "enum class Transfer",
        "{",
        "    linear,",
        "    srgb,   // IEC 61966-2-1",
        "    gamma,  // a pure power: linear = encoded^exponent",
        "};",
        "",
        "struct FileSpace",
        "{",
        "    std::string_view name;",
        "    std::string_view canonical;  // the MaterialX name this one spells (itself for the standard names)",
        "    Transfer transfer;",
        "    double exponent;",
        f"    std::array<std::array<double, 9>, {len(WORKING_SPACES)}> to_working;",
        "};",
        "",
        f"inline constexpr std::array<std::string_view, {len(WORKING_SPACES)}> working_space_names = {{"
        + ", ".join(f'"{s["name"]}"' for s in WORKING_SPACES) + "};",
        f'inline constexpr std::string_view default_document_space = "{DEFAULT_DOCUMENT_SPACE}";',
        "",
    ]
    rows = file_space_rows()
    lines.append(f"inline constexpr std::array<FileSpace, {len(rows)}> file_spaces = {{{{")
    for name, canonical, transfer, exponent, matrices in rows:
        lines.append(f'    {{"{name}", "{canonical}", Transfer::{transfer}, {exact(exponent)},')
        lines.append("     {{" + ", ".join(cpp_matrix(m) for m in matrices) + "}}},")
    lines.append("}};")
    lines.append("")
    lines.append("// Working space (index as above) -> linear Rec.709, the display's primaries.")
    lines.append(f"inline constexpr std::array<std::array<double, 9>, {len(WORKING_SPACES)}> working_to_display = {{{{")
    for m in display_matrices():
        lines.append(f"    {cpp_matrix(m)},")
    lines.append("}};")
    lines.append("")
    lines.append("}  // namespace openpbr::host::colour_table")
    lines.append("// clang-format on")
    lines.append("")
    return "\n".join(lines)


def js_matrix(m):
    return "[" + ", ".join(exact(v) for row in m for v in row) + "]"


JS_FUNCTIONS = """
// The names the loader accepts, for messages.
export const COLOUR_SPACE_NAMES = Object.keys(FILE_SPACES);

// Encoded file value -> linear, per channel (odd-extended below 0, as host/scene/colour_spaces.cpp).
function decode(space, value) {
  const magnitude = Math.abs(value);
  let linear = magnitude;
  if (space.transfer === 'srgb') linear = magnitude <= 0.04045 ? magnitude / 12.92 : ((magnitude + 0.055) / 1.055) ** 2.4;
  else if (space.transfer === 'gamma') linear = magnitude ** space.exponent;
  return value < 0 ? -linear : linear;
}

function multiply(m, v) {
  return [0, 1, 2].map((row) => m[3 * row] * v[0] + m[3 * row + 1] * v[1] + m[3 * row + 2] * v[2]);
}

// A color3 written in colour space `name` -> the working space, as float32 values (in double
// until the final rounding, as the C++ loader). null for a name not in the table.
export function toWorkingSpace(name, rgb, workingSpace = WORKING_SPACE) {
  const space = Object.hasOwn(FILE_SPACES, name) ? FILE_SPACES[name] : null;
  if (!space) return null;
  const matrix = space.toWorking[WORKING_SPACES.indexOf(workingSpace)];
  return multiply(matrix, rgb.map((value) => decode(space, value))).map(Math.fround);
}

// Linear Rec.709 (e.g. the preview scene's light and sky) -> the working space.
export function rec709ToWorkingSpace(rgb, workingSpace = WORKING_SPACE) {
  return toWorkingSpace('lin_rec709', rgb, workingSpace);
}
"""


def js_module(default_space):
    lines = [
        f"// {GENERATED_NOTE}",
        "// The MaterialX colour spaces the viewer's loader converts from (materialx.mjs), the same",
        "// table as host/scene/colour_space_table.h: per name, the transfer function and the linear",
        "// RGB matrix (row-major) into each working space, white adapted by Bradford where the white",
        "// points differ. WORKING_SPACE is the library's default (slang/openpbr_working_space.h), the",
        "// space the viewer's kernels are compiled for.",
        f"export const WORKING_SPACES = [{', '.join(repr(s['name']) for s in WORKING_SPACES)}];",
        f"export const WORKING_SPACE = '{default_space}';",
        f"export const DEFAULT_DOCUMENT_SPACE = '{DEFAULT_DOCUMENT_SPACE}';",
        "",
        "const FILE_SPACES = {",
    ]
    for name, canonical, transfer, exponent, matrices in file_space_rows():
        lines.append(f"  {name}: {{ canonical: '{canonical}', transfer: '{transfer}', exponent: {exact(exponent)}, "
                     f"toWorking: [{', '.join(js_matrix(m) for m in matrices)}] }},")
    lines.append("};")
    lines.append("")
    lines.append("// Working space -> linear Rec.709 (the display's primaries), per working space.")
    lines.append("export const WORKING_TO_DISPLAY = {")
    for space, m in zip(WORKING_SPACES, display_matrices()):
        lines.append(f"  {space['name']}: {js_matrix(m)},")
    lines.append("};")
    return "\n".join(lines) + "\n" + JS_FUNCTIONS


WGSL_BEGIN = "// ---- generated by tools/make_colour_tables.py: begin ----"
WGSL_END = "// ---- generated by tools/make_colour_tables.py: end ----"


def wgsl_block(default_space):
    index = [s["name"] for s in WORKING_SPACES].index(default_space)
    m = display_matrices()[index]
    # WGSL matrices are built from columns.
    columns = ", ".join(f"vec3f({', '.join(f'{m[r][c]:.9g}' for r in range(3))})" for c in range(3))
    return "\n".join([
        WGSL_BEGIN,
        f"// The library's default working space ({default_space}) -> linear Rec.709, the display's primaries.",
        f"const working_to_display = mat3x3f({columns});",
        WGSL_END,
    ])


def replace_wgsl_block(text, block):
    pattern = re.compile(re.escape(WGSL_BEGIN) + r".*?" + re.escape(WGSL_END), re.S)
    if not pattern.search(text):
        raise ValueError("viewer/display.wgsl has no generated block (markers missing)")
    return pattern.sub(lambda _: block, text)


def float32(value):
    return struct.unpack("<f", struct.pack("<f", value))[0]


SAMPLE_VALUES = [
    (0.8, 0.8, 0.8), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.18, 0.45, 0.9),
    (0.02, 0.003, 0.5), (4.0, 2.0, 1.0), (-0.25, 0.5, 1.5),
]


def conversion_cases():
    cases = []
    for name, canonical, transfer, exponent, matrices in file_space_rows():
        for working_index, space in enumerate(WORKING_SPACES):
            for sample in SAMPLE_VALUES:
                # The loaders read a file's numbers as float32 first, then convert in double.
                value = tuple(float32(v) for v in sample)
                linear = tuple(decode(transfer, exponent, v) for v in value)
                result = apply(matrices[working_index], linear)
                cases.append({"space": name, "working_space": space["name"], "value": list(value),
                              "expected": [float32(v) for v in result]})
    return {"note": GENERATED_NOTE, "cases": cases}


def encode(transfer, exponent, value):
    """Linear -> encoded file value, the inverse of decode."""
    magnitude = abs(value)
    if transfer == "linear":
        encoded = magnitude
    elif transfer == "srgb":
        encoded = magnitude * 12.92 if magnitude <= 0.04045 / 12.92 else 1.055 * magnitude ** (1.0 / 2.4) - 0.055
    else:
        encoded = magnitude ** (1.0 / exponent)
    return -encoded if value < 0.0 else encoded


# The colours of the per-space test documents, in linear Rec.709 (inside every space's gamut):
# a base colour and an HDR emission colour.
SAMPLE_DOCUMENT_COLOURS = {"base_color": (0.6, 0.3, 0.1), "emission_color": (4.0, 2.0, 1.0)}


def sample_document(name, primaries, white, transfer, exponent):
    """A MaterialX document in colour space `name` whose colours are SAMPLE_DOCUMENT_COLOURS."""
    rec709 = next(row for row in COLOUR_SPACES if row[0] == "lin_rec709")
    to_space = conversion(rec709[1], rec709[2], primaries, white)
    lines = [
        '<?xml version="1.0"?>',
        f"<!-- {GENERATED_NOTE} -->",
        f"<!-- The colours of SAMPLE_DOCUMENT_COLOURS (linear Rec.709) written in {name}. -->",
        f'<materialx version="1.39" colorspace="{name}">',
        f'  <open_pbr_surface name="{name}" type="surfaceshader" version="1.1.1">',
    ]
    for input_name, colour in SAMPLE_DOCUMENT_COLOURS.items():
        encoded = [encode(transfer, exponent, v) for v in apply(to_space, colour)]
        value = ", ".join(f"{v:.9g}" for v in encoded)
        lines.append(f'    <input name="{input_name}" type="color3" value="{value}" />')
    lines += ['    <input name="emission_luminance" type="float" value="100" />', "  </open_pbr_surface>",
              "</materialx>", ""]
    return "\n".join(lines)


def read_default_working_space(root):
    header = (root / "slang" / "openpbr_working_space.h").read_text()
    match = re.search(r"^\s*#\s*define\s+OPENPBR_WORKING_SPACE\s+OPENPBR_WORKING_SPACE_(\w+)\s*$", header, re.M)
    if not match:
        raise ValueError("slang/openpbr_working_space.h: no default '#define OPENPBR_WORKING_SPACE ...'")
    names = {s["macro"]: s["name"] for s in WORKING_SPACES}
    return names[match.group(1)]


def outputs(root):
    default_space = read_default_working_space(root)
    constants = [working_space_constants(space) for space in WORKING_SPACES]
    display_path = root / "viewer" / "display.wgsl"
    return {
        root / "slang" / "generated" / "openpbr_working_space_constants.h": slang_header(constants),
        root / "host" / "scene" / "colour_space_table.h": cpp_table(),
        root / "viewer" / "src" / "colour_spaces.mjs": js_module(default_space),
        display_path: replace_wgsl_block(display_path.read_text(), wgsl_block(default_space)),
        root / "tests" / "data" / "colour_conversions.json": json.dumps(conversion_cases(), indent=1) + "\n",
        **{root / "tests" / "data" / "colour_spaces" / f"{row[0]}.mtlx": sample_document(*row) for row in COLOUR_SPACES},
    }


def main(argv):
    check = "--check" in argv
    positional = [a for a in argv if a != "--check"]
    root = pathlib.Path(positional[0]) if positional else pathlib.Path(__file__).resolve().parent.parent
    stale = []
    for path, text in outputs(root).items():
        current = path.read_text() if path.exists() else None
        if current == text:
            continue
        stale.append(str(path.relative_to(root)))
        if not check:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
    if check and stale:
        print("make_colour_tables: out of date (run tools/make_colour_tables.py): " + ", ".join(stale),
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
