// lut_generator.h - generates the energy-compensation tables of slang/openpbr_lut.h by Monte
// Carlo integration, and reads / writes them as the shipped files:
//   slang/generated/openpbr_lut_values.inc  comma-separated float literals (array mode)
//   slang/generated/openpbr_lut.bin         raw float32, little-endian, no header (buffer mode)
//
// The tables are single-scattering directional albedos of GGX. Tables 0-3 are isotropic with
// alpha = max(r^2, 1e-4) (r = 0 gives the delta limit) for the view wo = (sqrt(1 - mu^2), 0, mu),
// mu = max(node, 1e-4). Tables 1-3 are at the relative IOR eta of their eta node
// (lut_eta_from_node: two halves, eta < 1 and eta > 1, each ending at the one-sided limit
// eta = 1 -/+ OPENPBR_LUT_UNIT_ETA_STEP) and the view cosine of their view node
// (lut_mu_from_view_coordinate: sqrt(mu) warped so that the critical cosine of eta is at 1/2,
// below eta = 1 also towards it on the scale of alpha):
//   0 E_ggx(mu, r)   reflection, F = 1:               E[G2(wo, wi) / G1(wo)], wi.z > 0
//   1 E_R(mu, r, x)  reflection, exact Fresnel:       E[F(wo.h) G2 / G1]
//   2 E_T0(mu, r, x) transmission, no Fresnel factor: E[G2(wo, wt) / G1(wo)], wt.z < 0, 0 under TIR
//   3 E_RT(mu, r, x) reflection + transmission:       E[F G2(wo, wr) / G1 + (1 - F) G2(wo, wt) / G1]
// Table 4 is the ratio of the F = 1 albedo of anisotropic GGX, OpenPBR's mapping
// alpha_t = max(r^2, 1e-4) sqrt(2 / (1 + (1 - a)^2)), alpha_b = max((1 - a) alpha_t, 1e-7), to
// that of the isotropic lobe alpha = max(r^2, 1e-4) (table 0's integrand), with a = 1 - (1 - c_a)^2
// and the view wo = (sin(theta) cos(phi), sin(theta) sin(phi), mu), cos^2(phi) the inverse of the
// azimuth coordinate openpbr_lut_azimuth_coordinate(mu, r, a, .) of slang/openpbr_lut.h:
//   4 E_ggx(mu, r, a, phi) / E_ggx(mu, r)  both estimated from the same sample points, so the
//                                          a = 0 slice is exactly 1
// The expectations are over visible normals h ~ D_wo (openpbr_sample_vndf_spherical_cap), so
// every sample weight lies in [0, 1]. Samples are a (0, 2)-sequence in base 2 (Sobol
// dimensions 1 and 2) with a per-cell random digital shift seeded by a hash of (table, cell):
// the result is deterministic and independent of the thread count. Sums are in double.
//
// Layout (the same as slang/openpbr_lut.h, for any sizes): one flat array, table 0 (2D,
// index = r_index * N2 + mu_index), tables 1, 2, 3 (3D, index = (eta_index * N3 + r_index)
// * N3 + mu_index, E3 eta nodes), then table 4 (4D, index = ((phi_index * M4 + a_index) * N4 + r_index) * N4
// + mu_index, N4 nodes on the mu and r axes, M4 on the anisotropy and azimuth axes); node i of
// an axis has coordinate i / (nodes - 1).
//
// This header does not include openpbr_lut.h: the generator reads the compiled layout in
// lut_generator.cpp only, in buffer mode, so it never depends on its own output.
// Link dependencies: TBB (CMake: find_package(TBB), target TBB::tbb), GLM (header-only);
// include directory: the repository root.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace openpbr::host {

// Table ids, equal to the order of the tables in the flat array.
enum LutTable : int
{
    lut_table_ggx_albedo = 0,               // E_ggx(mu, r), 2D
    lut_table_dielectric_reflection = 1,    // E_R(mu, r, x), 3D
    lut_table_dielectric_transmission = 2,  // E_T0(mu, r, x), 3D
    lut_table_dielectric_interface = 3,     // E_RT(mu, r, x), 3D
    lut_table_ggx_anisotropy_ratio = 4,     // E_ggx(mu, r, a, phi) / E_ggx(mu, r), 4D
};
inline constexpr int lut_table_count = 5;

// "ggx_albedo", "dielectric_reflection", "dielectric_transmission", "dielectric_interface",
// "ggx_anisotropy_ratio". Throws std::invalid_argument for an id outside [0, 4].
const char* lut_table_name(int table);

// The flat-array layout for given grid sizes (each >= 2).
struct LutLayout
{
    int size_2d = 0;             // nodes per axis of table 0, e.g. 32
    int size_3d = 0;             // nodes on the view and roughness axes of tables 1-3, e.g. 33
    int size_4d = 0;             // nodes on the mu and roughness axes of table 4, e.g. 16
    int size_4d_anisotropy = 0;  // nodes on the anisotropy and azimuth axes of table 4, e.g. 10
    int size_3d_eta = 0;         // nodes on the eta axis of tables 1-3 (even, >= 6), e.g. 48

    int dimensions(int table) const;           // 2, 3 or 4
    int size(int table) const;                 // nodes on the mu (and roughness) axis of that table
    int axis_size(int table, int axis) const;  // nodes on axis 0 (mu), 1 (r), 2 (x or a), 3 (phi)
    std::size_t count(int table) const;        // product of the axis sizes
    std::size_t offset(int table) const;       // first index of that table in the flat array
    std::size_t total_count() const;           // count of all tables
    bool operator==(const LutLayout& other) const
    {
        return size_2d == other.size_2d && size_3d == other.size_3d && size_4d == other.size_4d &&
               size_4d_anisotropy == other.size_4d_anisotropy && size_3d_eta == other.size_3d_eta;
    }
    bool operator!=(const LutLayout& other) const { return !(*this == other); }
};

// The layout compiled into the library (OPENPBR_LUT_2D_SIZE, OPENPBR_LUT_3D_SIZE,
// OPENPBR_LUT_4D_SIZE, OPENPBR_LUT_4D_ANISOTROPY_SIZE of slang/openpbr_lut.h): the only layout
// the shipped look-ups can read.
LutLayout compiled_lut_layout();

struct LutGeneratorOptions
{
    int size_2d = compiled_lut_layout().size_2d;  // other sizes give tables for comparison only
    int size_3d = compiled_lut_layout().size_3d;
    int size_4d = compiled_lut_layout().size_4d;
    int size_4d_anisotropy = compiled_lut_layout().size_4d_anisotropy;
    int size_3d_eta = compiled_lut_layout().size_3d_eta;
    // Per cell, e.g. 16384 (the shipped tables; 2.4x the cells of the earlier 25^3 tables, so
    // regeneration takes about 2 minutes of 2 cores); powers of two keep the (0, 2)-sequence a net.
    std::uint32_t samples = 1u << 14;
    int bits = 32;                 // 32: float32; 16: each value rounded to the nearest half (still stored as float)
    int threads = 0;               // 0: TBB's default (every core); n > 0: at most n worker threads
    std::uint64_t seed = 0;        // 0: the shipped tables; others give independent replicas (error estimates)
    bool progress = true;          // progress bar on stderr when stderr is a terminal
    bool progress_always = false;  // also when it is not (one line per 10%, e.g. for CI logs)

    LutLayout layout() const { return LutLayout{size_2d, size_3d, size_4d, size_4d_anisotropy, size_3d_eta}; }
};

// Every table of options.layout() in one flat array. Throws std::invalid_argument for sizes
// below 2 or above 1024 (2D) / 256 (3D) / 64 (4D), an odd eta size or one below 6, samples = 0, bits other than 16 and 32,
// threads < 0.
std::vector<float> generate_lut(const LutGeneratorOptions& options);

// The estimate of one table entry at arbitrary coordinates (mu, r, x, phi in [0, 1]; x is
// ignored by table 0, is the anisotropy coordinate of table 4 and for tables 1-3 gives the
// relative IOR lut_eta_from_coordinate(x), whose critical cosine warps the view coordinate mu
// there (lut_mu_from_view_coordinate); phi is read by table 4 only)
// with `samples` samples and digital-shift seed `seed`; generate_lut uses it with
// seed = lut_cell_seed(table, cell index within the table, options.seed). Exposed for tests and
// studies.
double estimate_lut_entry(int table, double mu, double r, double x, double phi, std::uint32_t samples, std::uint64_t seed);
double estimate_lut_entry(int table, double mu, double r, double x, std::uint32_t samples, std::uint64_t seed);
std::uint64_t lut_cell_seed(int table, std::size_t cell, std::uint64_t generator_seed = 0);
// The same estimate for tables 1-3 at a view cosine mu (floored at 1e-4), GGX alpha (floored
// at 1e-4) and relative IOR eta: what the look-up of slang/openpbr_lut.h approximates there.
double estimate_dielectric_entry(int table, double mu, double alpha, double eta, std::uint32_t samples, std::uint64_t seed);

// The node coordinate -> physical parameter maps of the tables.
double lut_eta_from_coordinate(double x);  // (1 + y) / (1 - y), y = 2 sgn(x - 0.5) (x - 0.5)^2: 1/3 at 0, 1 at 0.5, 3 at 1
// Relative IOR of eta node `index` of an axis of `eta_size` nodes (openpbr_lut_eta_node of
// slang/openpbr_lut.h inverted): 1/3 at 0, 1 - 2^-20 at eta_size / 2 - 1, 1 + 2^-20 at
// eta_size / 2, 3 at eta_size - 1.
double lut_eta_from_node(int index, int eta_size);
double lut_critical_cosine(double eta);  // openpbr_lut_critical_cosine in double
// The view coordinate u in [0, 1] of the 3D tables at view cosine mu, relative IOR eta and GGX
// alpha (openpbr_lut_view_coordinate with openpbr_lut_step_width, in double), and its inverse:
// the view cosine at u, floored at 1e-4. Below eta = 1 the axis depends on alpha (the warp
// towards the critical cosine on the scale of the step, slang/openpbr_lut.h).
double lut_view_coordinate(double mu, double eta, double alpha);
double lut_view_split(double eta);  // the coordinate of mu_c: 1/2 below eta = 1, OPENPBR_LUT_VIEW_SPLIT_ABOVE at and above
double lut_mu_from_view_coordinate(double u, double eta, double alpha);
double lut_alpha_from_coordinate(double r);       // max(r^2, 1e-4)
double lut_mu_from_coordinate(double mu);         // max(mu^2, 1e-4): the axis is sqrt(mu)
double lut_anisotropy_from_coordinate(double a);  // 1 - (1 - a)^2: the axis is 1 - sqrt(1 - anisotropy)
// The azimuth coordinate of table 4 in double precision (openpbr_lut_azimuth_coordinate of
// slang/openpbr_lut.h): mu the view cosine (floored at 1e-4), r the roughness, a the anisotropy,
// cos_phi_squared the view's squared azimuth cosine. Increasing in cos_phi_squared, 0 at 0 and
// 1 at 1.
double lut_azimuth_coordinate(double mu, double r, double a, double cos_phi_squared);
// Its inverse in cos_phi_squared (bisection to double precision).
double lut_cos_phi_squared_from_coordinate(double phi, double mu, double r, double a);

// Round to the nearest IEEE half-precision value (ties to even), returned as float.
float round_to_half(float value);

// One line describing a generation, e.g. "openpbr lutgen: 2D 32, 3D 25, 4D 16x16x10x10,
// 16384 samples/cell, float32, 73499 values" (plus ", seed N" for a non-zero seed), the comment
// line of the .inc file.
std::string describe(const LutGeneratorOptions& options);

// Writes one float literal per line, "%.8e" + "f" (9 significant digits: round-trips a float
// exactly; valid in GLSL, Slang, C++, CUDA and Metal), separated by commas, no trailing comma.
// A non-empty `comment` goes first as "//" lines. The file is written to a temporary name and
// renamed, so a failed write never leaves a truncated table. Throws std::runtime_error with the
// path on errors.
void write_lut_values_inc(const std::filesystem::path& path, const std::vector<float>& data,
                          const std::string& comment = std::string());

// Parses a file written by write_lut_values_inc ("//" comment lines, whitespace, an optional
// trailing comma and a missing "f" suffix are accepted). Throws std::runtime_error with the path
// (and line) when the file cannot be read or a value is malformed.
std::vector<float> read_lut_values_inc(const std::filesystem::path& path);

// Raw float32 values, little-endian, no header: the file size is 4 * count bytes. Written
// atomically as above.
void write_lut_binary(const std::filesystem::path& path, const std::vector<float>& data);

// Reads a file written by write_lut_binary. expected_count = 0 accepts any whole number of
// floats. Throws std::runtime_error naming the path when the file cannot be read, its size is
// not a multiple of 4, or it does not hold expected_count values.
std::vector<float> read_lut_binary(const std::filesystem::path& path,
                                   std::size_t expected_count = compiled_lut_layout().total_count());

// max |a[i] - b[i]| over the entries of one table. Throws std::invalid_argument when either
// array does not have layout.total_count() values.
double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b, int table,
                          const LutLayout& layout = compiled_lut_layout());

}  // namespace openpbr::host
