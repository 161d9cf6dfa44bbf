// accuracy_internal.h - what the parts of the accuracy study (host/studies/accuracy.h) share:
// the workloads, the tables of other sizes, the error statistics, the interleaved CPU timer and
// the measurement of each knob family. Not part of the host library's interface.
//   accuracy_workloads.cpp  materials, queries, tables, error statistics, the CPU timer
//   accuracy_families.cpp   one function per knob family
//   accuracy_floors.cpp     the model floors (random walk, real-time baselines, layering file)
//   accuracy_gpu.cpp        device times on lavapipe and SwiftShader
//   accuracy_pictures.cpp   the picture strips
//   accuracy.cpp            the run, the outputs
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "host/scene/material_library.h"
#include "host/studies/accuracy.h"
#include "host/studies/accuracy_variants.h"
#include "host/support/progress.h"

namespace openpbr::host::accuracy {

// ---- Workloads ---------------------------------------------------------------------------------

// Materials with queries over them: packed once (host::pack_materials), the form every variant
// and every GPU kernel reads.
struct Workload
{
    std::string name;  // e.g. "general"
    std::vector<Material> materials;
    std::vector<float> packed;
    std::vector<AccuracyQuery> queries;
};

// `count` queries over `materials`: views with cosines 0.05-1 at random azimuths, lights uniform
// on the sphere (transmission is evaluated too), the sampler's numbers uniform; fixed seed.
Workload make_workload(const std::string& name, std::vector<Material> materials, std::uint32_t count);

// A material from the spec defaults with the study's few fields set.
Material metal_material(float f0, float roughness);
Material glass_material(float roughness);
// The mix a renderer meets: plastic, metal, glass, coated metal, brushed metal at three
// roughnesses; with `thin_film` every one under a film (0.3-0.5 um of IOR 1.5).
std::vector<Material> general_materials(bool thin_film);
// The film-estimate stacks: a white diffuse base under a white film of IOR 1.4 under a white coat
// of IOR 1.6 (the film turns evanescent inside the lobe past its critical cosine 0.484), films of
// 0.3-1.5 um, coat and specular roughness 0.1-0.8.
std::vector<Material> film_stack_materials();

// The albedo grid of the compensation family: a white metal over roughness x view cosine.
struct AlbedoPoint
{
    float roughness = 0.5f;
    float mu = 1.0f;
};
std::vector<AlbedoPoint> compensation_grid(bool quick);

// ---- Tables ------------------------------------------------------------------------------------

// The tables the settings read besides the shipped ones, kept alive for the run.
struct StudyTables
{
    std::vector<float> size_16;    // table 0 at 16 x 16, the rest shipped
    std::vector<float> size_64;    // table 0 at 64 x 64
    std::vector<float> reference;  // table 0 at 256 x 256 by quadrature in double
    std::vector<std::uint16_t> halves;
};
// Builds (or reads from the cache) the tables and points the variants at them.
StudyTables make_study_tables(const AccuracyOptions& options);
// The flat table (tables 0-5) a setting binds on a GPU; the 16-bit one as 32-bit words.
std::vector<std::byte> table_bytes(const StudyTables& tables, AccuracyTable table);
// Size of table 0 of the reference (256) and the quadrature's nodes per axis.
constexpr int reference_table_size = 256;
// E_ggx(mu, alpha) of GGX reflection with F = 1 (single scattering, height-correlated Smith) by
// a midpoint quadrature in double over the distribution of normals (n x n nodes, graded towards
// grazing microfacets): within 1e-4 of the converged value for view cosines from 0.01
// (docs/accuracy-vs-time.md "How measured").
double ggx_albedo_quadrature(double mu, double alpha, int n);

// ---- Errors ------------------------------------------------------------------------------------

struct RelativeErrors
{
    double median = 0.0;
    double p99 = 0.0;
    double max = 0.0;
};
// Relative differences of `values` from `reference` over entries whose reference exceeds 1e-3
// (smaller values are dominated by float rounding of cancelling terms).
RelativeErrors relative_errors(const std::vector<float>& values, const std::vector<float>& reference);

// ---- CPU timing --------------------------------------------------------------------------------

enum class Operation
{
    eval,
    sample,
};

// Interleaved CPU timing: every job (a variant, a workload, an operation) is timed once per
// round; a burst of load from other processes then slows one round of every job instead of
// every round of one. A round times the workload in chunks of timing_chunk queries, each the
// best of three runs, and sums them: a chunk (under a millisecond) fits in one time slice of a
// loaded machine, where a whole batch of an expensive workload (80 ms of filmed queries) was
// always preempted and read up to 9 times its time on 2 cores at load 20. Keeps the best and
// the median over the rounds.
class CpuTimer
{
  public:
    std::size_t add(const BsdfVariant& variant, const Workload& workload, Operation operation);
    void run(int rounds, ProgressReporter& progress);
    AccuracyTime time(std::size_t job) const;

    static constexpr std::size_t timing_chunk = 16;  // queries per timed chunk, e.g. 16

  private:
    struct Job
    {
        const BsdfVariant* variant;
        const Workload* workload;
        Operation operation;
        std::vector<double> ns;
    };
    std::vector<Job> jobs_;
    // Each workload's queries cut into chunks, made at the first job that uses it.
    std::map<const Workload*, std::vector<std::vector<AccuracyQuery>>> chunks_;
};

// ---- The families ------------------------------------------------------------------------------

// What every family's measurement reads.
struct StudyContext
{
    const AccuracyOptions& options;
    const std::vector<BsdfVariant>& variants;
    const Workload& general;      // compensation, storage, fast math, precision
    const Workload& metals;       // sampling
    const Workload& films;        // thin film
    const Workload& film_stacks;  // film estimate
    const StudyTables& tables;
    CpuTimer& timer;
};

// A family as measured, with the CPU timing job of each setting (filled after the timer runs).
struct FamilyMeasurement
{
    AccuracyFamily family;
    std::vector<std::size_t> timing_jobs;  // one per setting
    std::string workload;                  // the Workload name its GPU times use
    Operation operation = Operation::eval;
};

const BsdfVariant& variant_named(const std::vector<BsdfVariant>& variants, const std::string& name);

FamilyMeasurement measure_compensation(const StudyContext& context);
FamilyMeasurement measure_table_storage(const StudyContext& context);
FamilyMeasurement measure_fast_math(const StudyContext& context);
FamilyMeasurement measure_precision(const StudyContext& context);
FamilyMeasurement measure_thin_film(const StudyContext& context);
FamilyMeasurement measure_film_estimate(const StudyContext& context);
FamilyMeasurement measure_sampling(const StudyContext& context);

// ---- Model floors -----------------------------------------------------------------------------

// The compensation model (shipped and with exact E_ggx, no compensation, the analytic fit) and
// real-time baselines against the microsurface random walk, on metals over roughness x view
// cosine x F0; times from the families' CPU jobs where a variant has one.
AccuracyFloor measure_compensation_floor(const StudyContext& context, const std::vector<AccuracyFamily>& families);
// The layering floor from `openpbr accuracy layering`'s JSON, or a note when it is absent.
AccuracyFloor read_layering_floor(const std::filesystem::path& path);

// ---- GPU ---------------------------------------------------------------------------------------

// Device times of every setting that has a kernel: lavapipe (Vulkan timestamps) and SwiftShader
// (WebGPU timestamps), on the workload of its family; also each lavapipe result's error against
// the same setting on the CPU. Rows that cannot run here are left out with a note on stderr.
void measure_gpu_times(const StudyContext& context, const StudyTables& tables, std::vector<FamilyMeasurement>& families,
                       ProgressReporter& progress);
// Kernels the GPU part compiles (one per setting with a kernel), for the progress bar.
std::size_t gpu_kernel_count(const std::vector<BsdfVariant>& variants);

// ---- Pictures ----------------------------------------------------------------------------------

// The picture strips (docs/accuracy-vs-time.md "Pictures") into options.pictures_directory.
void write_picture_strips(const StudyContext& context);

}  // namespace openpbr::host::accuracy
