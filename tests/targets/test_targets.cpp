// Targets that can be executed here: the HLSL library's conformance kernel (glslang's HLSL
// front end) and the consumer example (Slang SPIR-V) on Vulkan, the CUDA paths where a CUDA
// device exists; plus the option handling of `openpbr compile`, and its WGSL specialized when
// generated against the built WGSL with the toggles set as `override` constants.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "host/gpu/compile_targets.h"
#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/gpu/cuda_conformance.h"
#include "host/scene/material_library.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "host/scene/features.h"
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

std::string file_text(const std::filesystem::path& path)
{
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// Toggles in both of WGSL's forms (docs/specialization.md "WGSL: overrides or folded when generated"): the kernels as built,
// every toggle an `override`, run with those outside a set false at pipeline creation (PathBatch::feature_mask), and the
// kernels `openpbr compile --target wgsl --specialize` generated for the set, with no `override` left, give the same results
// on both WebGPU paths. The batch holds materials inside the set and one that needs a toggle outside it (the thin film): on
// that one's queries the results must lie far closer to the CPU build with the set's toggles (ScopedFeatureMask) than to the
// CPU build with every toggle on, which shows that both forms really switched it off, rather than both running every toggle
// on.
TEST(Targets, WgslSpecializedWhenGeneratedMatchesOverrideConstants)
{
    const std::vector<std::string> path_names = {"slang-wgsl", "wgsl-library"};
    ExecutionPaths built(ExecutionPathSettings{OPENPBR_KERNEL_DIR});
    for (const std::string& name : path_names)
    {
        const std::string reason = built.path(name).unavailable_reason();
        if (!reason.empty())
        {
            GTEST_SKIP() << name << ": " << reason;
        }
    }
    const std::uint32_t mask = parse_feature_names({"coat", "metal"});
    std::vector<Material> materials;
    std::size_t outside_material = 0;
    bool outside_found = false;
    for (const Material& material : conformance_materials(load_material_directory(OPENPBR_MATERIALS_DIR)))
    {
        const std::uint32_t needs = required_feature_mask(material);
        if ((needs & ~mask) == 0)
        {
            materials.push_back(material);
        }
        else if (!outside_found && (needs & OPENPBR_FEATURE_BIT_THIN_FILM) != 0)
        {
            outside_material = materials.size();
            materials.push_back(material);
            outside_found = true;
        }
    }
    ASSERT_TRUE(outside_found) << "no conformance material needs the thin film";
    // Every toggle of the set is used by some material of the batch.
    ASSERT_EQ(scene_feature_mask(materials) & mask, mask);

    // 512 queries: SwiftShader's pipeline builds are the cost, not the batch.
    const std::vector<float> packed = pack_materials(materials);
    const std::vector<float> queries = make_queries(512, materials.size(), 11);
    const std::vector<float> cpu = run_conformance_cpu(queries, packed);
    const std::vector<float> cpu_specialized = [&] {
        const ScopedFeatureMask scoped(mask);
        return run_conformance_cpu(queries, packed);
    }();
    // The override form first, before the compile: where Dawn finds no adapter at all the test
    // stops here. Where SwiftShader is installed (scripts/setup.sh, CI) the paths must run.
    std::map<std::string, std::vector<float>> overridden;
    for (const std::string& name : path_names)
    {
        PathBatch with_overrides{queries, packed};
        with_overrides.feature_mask = mask;
        try
        {
            overridden[name] = built.path(name).run(with_overrides).results;
        }
        catch (const PathUnavailable& unavailable)
        {
            ASSERT_FALSE(std::filesystem::exists(swiftshader_vulkan_driver()))
                << name << " did not run although SwiftShader is installed: " << unavailable.what();
            GTEST_SKIP() << name << ": " << unavailable.what();
        }
    }

    CompileTargetsOptions options = default_compile_targets_options();
    options.targets = {"wgsl"};
    // Per process: another build's ctest may run the same test at the same time.
    options.output_directory =
        (std::filesystem::temp_directory_path() / ("openpbr-wgsl-specialized-" + std::to_string(getpid()))).string();
    options.feature_mask = mask;
    // The two kernels the paths run (two compiles, not five: the example, the render kernel and
    // the library are not run here).
    options.conformance_kernels_only = true;
    compile_targets(options);
    const std::filesystem::path generated_directory = std::filesystem::path(options.output_directory) / "wgsl";
    // An `override` is declared "@id(N) override EnableCoat : bool = true;".
    for (const char* kernel : {"conformance.slang.wgsl", "conformance.library.wgsl"})
    {
        EXPECT_NE(file_text(std::filesystem::path(OPENPBR_KERNEL_DIR) / kernel).find("@id("), std::string::npos)
            << kernel << " as built";
        EXPECT_EQ(file_text(generated_directory / kernel).find("@id("), std::string::npos)
            << kernel << " specialized when generated";
    }

    ExecutionPaths generated(ExecutionPathSettings{generated_directory.string()});
    for (const std::string& name : path_names)
    {
        const std::vector<float>& with_overrides = overridden[name];
        const std::vector<float> folded = generated.path(name).run(PathBatch{queries, packed}).results;
        ASSERT_EQ(with_overrides.size(), cpu.size()) << name;
        ASSERT_EQ(folded.size(), cpu.size()) << name;
        std::size_t differing = 0;
        double from_specialized_cpu = 0.0;  // summed over the outside material's eval slots
        double from_full_cpu = 0.0;
        for (std::size_t query = 0; query < cpu.size() / result_floats; ++query)
        {
            for (std::size_t slot = query * result_floats; slot < (query + 1) * result_floats; ++slot)
            {
                differing += std::memcmp(&with_overrides[slot], &folded[slot], sizeof(float)) != 0 ? 1 : 0;
            }
            if (std::size_t(queries[query * query_floats]) == outside_material)
            {
                // Eval's diffuse and specular (slots 0-5): finite for every query.
                for (std::size_t slot = query * result_floats; slot < query * result_floats + 6; ++slot)
                {
                    from_specialized_cpu += std::fabs(double(folded[slot]) - double(cpu_specialized[slot]));
                    from_full_cpu += std::fabs(double(folded[slot]) - double(cpu[slot]));
                }
            }
        }
        std::cout << name << ": summed eval difference on the thin-film material's queries from the CPU build with the "
                  << "set's toggles " << from_specialized_cpu << ", with every toggle " << from_full_cpu << "\n";
        EXPECT_EQ(differing, 0u) << name << ": results of the two forms differ";
        // Measured (2026-11-27, both paths, SwiftShader): 0 from the CPU build with the set's
        // toggles against 1.395 with every toggle on; a tenth leaves room for WGSL's math.
        EXPECT_LT(from_specialized_cpu * 10.0, from_full_cpu)
            << name << ": the thin film was not switched off (summed eval difference from the CPU build with the "
            << "set's toggles " << from_specialized_cpu << ", with every toggle " << from_full_cpu << ")";
    }
    std::filesystem::remove_all(options.output_directory);
}

// The compile-time form of a toggle set has one rule: the C++ host's list
// (specialization_defines, which `openpbr compile --specialize` passes) is the one the browser
// viewer builds in the page from slang/openpbr_features.h (viewer/features.mjs).
TEST(Targets, SpecializationDefinesAreTheViewers)
{
    const CompileTargetsOptions tools = default_compile_targets_options();
    const std::string source = tools.source_directory;
    for (const std::uint32_t mask : {0u, std::uint32_t(OPENPBR_FEATURE_BIT_COAT | OPENPBR_FEATURE_BIT_METAL),
                                     OPENPBR_FEATURE_BIT_THIN_FILM, full_feature_mask()})
    {
        const std::string command = tools.node +
                                    " --input-type=module -e \"import { readFeatureToggles, "
                                    "specializationDefines } from '" +
                                    source + "/viewer/features.mjs'; " +
                                    "console.log(specializationDefines(readFeatureToggles('" + source +
                                    "/slang/openpbr_features.h'), " + std::to_string(mask) + ").join(' '))\"";
        FILE* const pipe = popen(command.c_str(), "r");
        ASSERT_NE(pipe, nullptr) << command;
        std::string viewer;
        char buffer[512];
        while (std::fgets(buffer, sizeof(buffer), pipe) != nullptr)
        {
            viewer += buffer;
        }
        ASSERT_EQ(pclose(pipe), 0) << command;
        std::string host;
        for (const std::string& define : specialization_defines(mask))
        {
            host += (host.empty() ? "" : " ") + define;
        }
        EXPECT_EQ(viewer, host + "\n") << "toggle set " << feature_set_label(mask);
    }
}

}  // namespace
