// The module's gradients on the GPU paths (targets/autodiff/gradients_gpu.slang, tables as buffers)
// against differences of the double-precision C++ build: eval and pdf with prepared inputs in
// reverse mode (d/d(light) and d/d(the prepared lobe weights)), on lavapipe (Slang's SPIR-V) and on
// WebGPU (Slang's WGSL through Dawn on SwiftShader, where installed), for every lobe alone and the
// named special points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "host/checks/conformance.h"
#include "host/checks/execution_path.h"
#include "host/gpu/cuda_conformance.h"
#include "host/gpu/vulkan_runner.h"
#include "targets/autodiff/openpbr_gradient_records.h"
#include "tests/autodiff/gradient_check.h"

namespace openpbr::test {
namespace {

using host::gradients::value_diffuse;
using host::gradients::value_pdf;
using host::gradients::value_specular;
using host::gradients::ValueRecord;

// The GPU's float32 derivatives against the double build's differences: the CPU's tolerance
// (test_gradients.cpp, where the largest error over the same corpus was 0.27 of it).
constexpr Tolerance tolerance{2e-3, 2e-5, 1e-6};

std::vector<GradientQuery> gpu_queries()
{
    std::vector<GradientQuery> queries = lobe_queries();
    const std::vector<GradientQuery> special = special_point_queries();
    queries.insert(queries.end(), special.begin(), special.end());
    return queries;
}

// The scalar of result component `component` (eval's R, G, B: diffuse + specular; 3: the pdf).
ValueRecord component_weights(int component)
{
    ValueRecord weights{};
    if (component == 3)
    {
        weights[value_pdf] = 1.0f;
    }
    else
    {
        weights[value_diffuse + component] = 1.0f;
        weights[value_specular + component] = 1.0f;
    }
    return weights;
}

// The batch of the kernel: each query's material packed once, one record per query.
struct GpuBatch
{
    std::vector<float> queries;
    std::vector<float> materials;
};

GpuBatch make_batch(const std::vector<GradientQuery>& queries)
{
    GpuBatch batch;
    for (std::size_t index = 0; index < queries.size(); ++index)
    {
        const GradientQuery& query = queries[index];
        batch.materials.insert(batch.materials.end(), query.material.begin(), query.material.end());
        const float record[OPENPBR_GRADIENT_QUERY_FLOATS] = {
            float(index), query.view[0], query.view[1], query.view[2], query.light[0], query.light[1], query.light[2],
            0.0f,         0.0f,          0.0f,          1.0f};
        batch.queries.insert(batch.queries.end(), record, record + OPENPBR_GRADIENT_QUERY_FLOATS);
    }
    return batch;
}

struct GpuTotals
{
    int checked = 0;
    int singular = 0;
    double worst = 0.0;
    std::string worst_where;
    std::vector<std::string> failures;
};

void record(GpuTotals& totals, const Comparison& comparison, double derivative, const std::string& where)
{
    ++totals.checked;
    if (comparison.agreement == Agreement::singular)
    {
        ++totals.singular;
        return;
    }
    if (comparison.error > totals.worst)
    {
        totals.worst = comparison.error;
        totals.worst_where = where;
    }
    if (comparison.agreement == Agreement::failed || !std::isfinite(derivative))
    {
        char line[512];
        std::snprintf(line, sizeof line, "%s: GPU %.9g, differences %.9g", where.c_str(), derivative, comparison.reference);
        totals.failures.push_back(line);
    }
}

static_assert(OPENPBR_GRADIENT_RESULT_FLOATS == 6 + 3 * 6, "d/d(light) twice, then 3 floats per prepared field");

// The prepared kernel's d/d(light): of the eval cotangent (slots 0-2) and of the pdf (3-5); then the
// eval cotangent's d/d(prepared field) for each channel of OPENPBR_GRADIENT_PREPARED_FIELDS (slots
// 6-23), against differences of the double build with that field moved between prepare and eval.
GpuTotals check_prepared_results(const std::vector<GradientQuery>& queries, const std::vector<float>& results)
{
    GpuTotals totals;
    ValueRecord eval_weights{};
    const float channel_weights[] = {1.0f, 0.8f, 0.6f};  // OPENPBR_GRADIENT_EVAL_WEIGHTS
    for (std::size_t channel = 0; channel < 3; ++channel)
    {
        eval_weights[value_diffuse + channel] = channel_weights[channel];
        eval_weights[value_specular + channel] = channel_weights[channel];
    }
    const ValueRecord pdf_weights = component_weights(3);
    for (std::size_t index = 0; index < queries.size(); ++index)
    {
        for (std::size_t axis = 0; axis < 3; ++axis)
        {
            const CheckedInput input{CheckedInput::Kind::light, axis, std::string("light.") + "xyz"[axis]};
            const float* result = &results[index * OPENPBR_GRADIENT_RESULT_FLOATS];
            record(totals, compare_with_differences(queries[index], eval_weights, input, result[axis], tolerance),
                   result[axis], queries[index].label + " prepared d(eval)/d" + input.name);
            record(totals, compare_with_differences(queries[index], pdf_weights, input, result[3 + axis], tolerance),
                   result[3 + axis], queries[index].label + " prepared d(pdf)/d" + input.name);
        }
        for (std::size_t slot = 0; slot < 3 * double_prepared_field_count(); ++slot)
        {
            const std::string name = std::string(double_prepared_field_name(slot / 3)) + "." + "rgb"[slot % 3];
            const CheckedInput input{CheckedInput::Kind::prepared, slot, name};
            const float derivative = results[index * OPENPBR_GRADIENT_RESULT_FLOATS + 6 + slot];
            record(totals, compare_with_differences(queries[index], eval_weights, input, derivative, tolerance), derivative,
                   queries[index].label + " prepared d(eval)/d" + name);
        }
    }
    return totals;
}

void report(const char* what, const GpuTotals& totals)
{
    std::printf("%s: %d derivatives, %d at singular points, %zu failed, worst %.3f of the tolerance (%s)\n", what,
                totals.checked, totals.singular, totals.failures.size(), totals.worst, totals.worst_where.c_str());
    for (std::size_t index = 0; index < std::min<std::size_t>(totals.failures.size(), 40); ++index)
    {
        std::printf("  FAILED %s\n", totals.failures[index].c_str());
    }
}

// Slang names a SPIR-V module's single entry point "main" (OpEntryPoint ... "main"), whatever the
// Slang function is called; WGSL keeps the function's name.
std::vector<float> run_on_lavapipe(const GpuBatch& batch)
{
    std::string error;
    // Without the validation layer: its shader checks crash (SIGSEGV in libVkLayer_khronos_validation,
    // Debian 12) on this 0.55 MB module, which spirv-val --target-env vulkan1.2 accepts.
    std::optional<host::VulkanContext> context = host::VulkanContext::create({false, "llvmpipe"}, &error);
    if (!context)
    {
        throw std::runtime_error("no lavapipe device: " + error);
    }
    host::ComputePipelineDescription description;
    description.spirv_words = host::load_spirv_file(std::string(OPENPBR_KERNEL_DIR) + "/gradients_gpu.spv");
    description.entry_point = "main";
    description.bindings = {{0, false}, {1, false}, {2, false}, {3, false}, {4, false}, {5, false}};
    host::ComputePipeline pipeline(*context, description);
    const host::ConformanceDispatch dispatch =
        host::dispatch_conformance_pipeline(pipeline, batch.queries, batch.materials, 1, {});
    std::printf("lavapipe: first dispatch (llvmpipe's build included) %.0f ms\n", dispatch.timing.first_dispatch_ms);
    return dispatch.results;
}

TEST(GradientsGpu, PreparedEvalReverseModeOnLavapipeMatchesDifferences)
{
    const std::vector<GradientQuery> queries = gpu_queries();
    const GpuBatch batch = make_batch(queries);
    const GpuTotals totals = check_prepared_results(queries, run_on_lavapipe(batch));
    report("lavapipe, eval with prepared inputs, reverse mode", totals);
    EXPECT_TRUE(totals.failures.empty());
}

TEST(GradientsGpu, PreparedEvalReverseModeOnWebGpuMatchesDifferences)
{
    const std::vector<GradientQuery> queries = gpu_queries();
    const GpuBatch batch = make_batch(queries);
    const std::vector<std::string> command = {
        OPENPBR_NODE,   std::string(OPENPBR_SOURCE_DIR) + "/targets/wgsl/dispatch_conformance.mjs",
        "-path",        "gradients-wgsl",
        "-kernel",      std::string(OPENPBR_KERNEL_DIR) + "/gradients_gpu.wgsl",
        "-entry",       "gradient_prepared_main",
        "-swiftshader", host::swiftshader_vulkan_driver(),
        "-repeats",     "1",
        "-dir"};
    const std::vector<host::ExternalPathResult> runs =
        host::run_conformance_program(command, {"gradients-wgsl"}, batch.queries, batch.materials);
    if (!runs.front().executed)
    {
        // Where SwiftShader is installed (scripts/setup.sh, CI) the WebGPU path must run.
        ASSERT_FALSE(std::filesystem::exists(host::swiftshader_vulkan_driver()))
            << "not executed although SwiftShader is installed: " << runs.front().note;
        GTEST_SKIP() << "not executed: " << runs.front().note;
    }
    std::printf("%s\n", runs.front().note.c_str());
    const GpuTotals totals = check_prepared_results(queries, runs.front().results);
    report("WebGPU, eval with prepared inputs, reverse mode", totals);
    EXPECT_TRUE(totals.failures.empty());
}

}  // namespace
}  // namespace openpbr::test
