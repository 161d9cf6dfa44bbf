// Targets that can be executed here: the HLSL library's conformance kernel (glslang's HLSL
// front end) and the consumer example (Slang SPIR-V) on Vulkan, the CUDA paths where a CUDA
// device exists; plus the option handling of `openpbr compile`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "host/gpu/compile_targets.h"
#include "host/checks/conformance.h"
#include "host/gpu/cuda_conformance.h"
#include "host/scene/material_library.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "slang/openpbr.h"

namespace {

using namespace openpbr::host;

constexpr std::size_t query_count = 4096;
constexpr int query_floats = 11;  // OPENPBR_QUERY_FLOATS, targets/kernels/openpbr_conformance_kernel.h
constexpr int result_floats = 24;

struct Batch
{
    std::vector<float> queries;
    std::vector<float> materials;
    std::vector<float> cpu_results;
};

const Batch& batch()
{
    static const Batch cached = [] {
        Batch b;
        const std::vector<Material> materials = conformance_materials(load_material_directory(OPENPBR_MATERIALS_DIR));
        b.materials = pack_materials(materials);
        b.queries = make_queries(query_count, materials.size(), 7);
        b.cpu_results = run_conformance_cpu(b.queries, b.materials);
        return b;
    }();
    return cached;
}

double relative_error(float gpu, float cpu)
{
    return std::fabs(double(gpu) - double(cpu)) / std::max(std::fabs(double(cpu)), 1e-3);
}

// Eval, pdf and emission of every query; the sample outputs where the lobes agree.
void expect_matches_cpu(const std::vector<float>& results, const char* what)
{
    const Batch& b = batch();
    ASSERT_EQ(results.size(), b.cpu_results.size());
    double worst = 0.0;
    std::size_t mismatches = 0;
    for (std::size_t q = 0; q < query_count; ++q)
    {
        const float* gpu = results.data() + q * result_floats;
        const float* cpu = b.cpu_results.data() + q * result_floats;
        const bool lobes_agree = gpu[17] == cpu[17];
        mismatches += lobes_agree ? 0 : 1;
        for (int slot = 0; slot < 21; ++slot)
        {
            if (slot >= 7 && slot < 17 && !lobes_agree)
            {
                continue;
            }
            ASSERT_TRUE(std::isfinite(gpu[slot])) << what << ": query " << q << " slot " << slot;
            worst = std::max(worst, relative_error(gpu[slot], cpu[slot]));
        }
    }
    EXPECT_LE(worst, 1e-3) << what;
    EXPECT_LE(double(mismatches) / double(query_count), 1e-3) << what;
}

std::optional<VulkanContext> vulkan(std::string* error)
{
    VulkanOptions options;
    options.enable_validation = true;
    return VulkanContext::create(options, error);
}

TEST(Targets, HlslLibraryKernelMatchesCpu)
{
    std::string error;
    std::optional<VulkanContext> context = vulkan(&error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    const Batch& b = batch();
    ComputePipelineDescription description;
    description.spirv_words = load_spirv_file(std::string(OPENPBR_KERNEL_DIR) + "/conformance.hlsl.spv");
    description.bindings = {{0, false}, {1, false}, {2, false}, {3, false}, {4, false}, {5, false}};
    ComputePipeline pipeline(*context, description);
    std::vector<std::byte> lut = to_bytes(shipped_lut());
    std::vector<std::byte> fuzz = to_bytes(shipped_fuzz_ltc());
    std::vector<std::byte> queries = to_bytes(b.queries);
    std::vector<std::byte> materials = to_bytes(b.materials);
    std::vector<std::byte> parameters = to_bytes(std::vector<std::uint32_t>{std::uint32_t(query_count), 0, 0, 0});
    std::vector<std::byte> results(query_count * result_floats * sizeof(float));
    run(pipeline,
        {{0, &lut, false},
         {1, &fuzz, false},
         {2, &queries, false},
         {3, &materials, false},
         {4, &parameters, false},
         {5, &results, true}},
        std::uint32_t((query_count + 63) / 64));
    expect_matches_cpu(from_bytes<float>(results), "hlsl library kernel");
    EXPECT_TRUE(context->validation_messages().empty()) << context->validation_messages().front();
}

// examples/shade_batch.slang through Slang's SPIR-V (build/targets/spirv/shade_batch.spv):
// push-constant query count, both specialization constants, records of 64 and 96 bytes.
TEST(Targets, ExampleShadeBatchMatchesCpu)
{
    std::string error;
    std::optional<VulkanContext> context = vulkan(&error);
    if (!context)
    {
        GTEST_SKIP() << "no Vulkan device: " << error;
    }
    const Batch& b = batch();
    std::vector<float> records(query_count * 16, 0.0f);
    for (std::size_t q = 0; q < query_count; ++q)
    {
        const float* in = b.queries.data() + q * query_floats;
        float* out = records.data() + q * 16;
        std::copy(in + 1, in + 4, out);       // view
        out[3] = in[10];                      // exterior IOR
        std::copy(in + 4, in + 7, out + 4);   // light
        std::copy(in + 7, in + 10, out + 8);  // u
        const std::uint32_t material = std::uint32_t(in[0]);
        std::memcpy(out + 12, &material, sizeof(material));
    }
    for (const bool sample : {true, false})
    {
        ComputePipelineDescription description;
        description.spirv_words = load_spirv_file(std::string(OPENPBR_TARGETS_DIR) + "/spirv/shade_batch.spv");
        description.bindings = {{0, false}, {1, false}, {2, false}, {3, false}, {4, false}};
        description.push_constant_size = 4;
        description.specialization_constants = {SpecializationConstant::of_bool(16, true),
                                                SpecializationConstant::of_bool(17, sample)};
        ComputePipeline pipeline(*context, description);
        std::vector<std::byte> lut = to_bytes(shipped_lut());
        std::vector<std::byte> fuzz = to_bytes(shipped_fuzz_ltc());
        std::vector<std::byte> materials = to_bytes(b.materials);
        std::vector<std::byte> queries = to_bytes(records);
        std::vector<std::byte> results(query_count * 24 * sizeof(float));
        DispatchRequest request;
        request.groups_x = std::uint32_t((query_count + 63) / 64);
        request.push_constants = to_bytes(std::vector<std::uint32_t>{std::uint32_t(query_count)});
        run(pipeline,
            {{0, &lut, false}, {1, &fuzz, false}, {2, &materials, false}, {3, &queries, false}, {4, &results, true}},
            request);
        const std::vector<float> out = from_bytes<float>(results);
        double worst = 0.0;
        std::size_t mismatches = 0;
        for (std::size_t q = 0; q < query_count; ++q)
        {
            const float* gpu = out.data() + q * 24;
            const float* cpu = b.cpu_results.data() + q * result_floats;
            const float expected[] = {cpu[0], cpu[1], cpu[2], cpu[6], cpu[3], cpu[4], cpu[5]};
            const float got[] = {gpu[0], gpu[1], gpu[2], gpu[3], gpu[4], gpu[5], gpu[6]};
            for (int k = 0; k < 7; ++k)
            {
                worst = std::max(worst, relative_error(got[k], expected[k]));
            }
            for (int k = 0; k < 3; ++k)
            {
                worst = std::max(worst, relative_error(gpu[16 + k], cpu[18 + k]));  // emission
            }
            std::uint32_t lobe = 0;
            std::memcpy(&lobe, gpu + 20, sizeof(lobe));
            if (!sample)
            {
                EXPECT_EQ(gpu[11], 0.0f) << "sample pdf written with SHADE_BATCH_SAMPLE = false";
                continue;
            }
            if (float(lobe) != cpu[17])
            {
                ++mismatches;
                continue;
            }
            for (int k = 0; k < 3; ++k)
            {
                worst = std::max(worst, relative_error(gpu[8 + k], cpu[7 + k]));                  // direction
                worst = std::max(worst, relative_error(gpu[12 + k], cpu[10 + k] + cpu[13 + k]));  // weight
            }
            worst = std::max(worst, relative_error(gpu[11], cpu[16]));  // sample pdf
        }
        EXPECT_LE(worst, 1e-3) << "sample " << sample;
        EXPECT_LE(double(mismatches) / double(query_count), 1e-3);
    }
    EXPECT_TRUE(context->validation_messages().empty()) << context->validation_messages().front();
}

// The CUDA paths: executed where a CUDA device exists, otherwise skipped with the program's
// own words ("skipped: no CUDA device ...") or because nvcc was not found.
TEST(Targets, CudaPathsMatchCpuWhereADeviceExists)
{
    const Batch& b = batch();
    const std::vector<ExternalPathResult> paths =
        run_cuda_conformance_program(default_cuda_conformance_program(), b.queries, b.materials);
    ASSERT_EQ(paths.size(), 2u);
    EXPECT_EQ(paths[0].name, "cuda");
    EXPECT_EQ(paths[1].name, "slang-cuda");
    std::string skipped;
    for (const ExternalPathResult& path : paths)
    {
        std::printf("%s: %s\n", path.name.c_str(), path.note.c_str());
        if (!path.executed)
        {
            EXPECT_TRUE(path.note.rfind("skipped: no CUDA device", 0) == 0 || path.note.rfind("not built", 0) == 0)
                << path.note;
            skipped += path.name + ": " + path.note + "; ";
            continue;
        }
        expect_matches_cpu(path.results, path.name.c_str());
    }
    if (!skipped.empty())
    {
        GTEST_SKIP() << skipped;
    }
}

TEST(Targets, CompileRejectsUnknownTarget)
{
    CompileTargetsOptions options = default_compile_targets_options();
    options.output_directory = (std::filesystem::temp_directory_path() / "openpbr-compile-test").string();
    options.targets = {"dxil"};
    EXPECT_THROW(compile_targets(options), std::invalid_argument);
    EXPECT_EQ(compile_target_names(), (std::vector<std::string>{"spirv", "hlsl", "metal", "cuda", "glsl", "wgsl"}));
}

}  // namespace
