// Preview path tracer: white furnace on the CPU backend, CPU versus Vulkan on the same seeds,
// determinism, and the label font.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "host/scene/material_library.h"
#include "host/preview/render.h"
#include "host/preview/render_font.h"

namespace {

using namespace openpbr::host;

RenderSettings quiet_settings()
{
    RenderSettings settings;
    settings.progress = false;
    settings.kernel_directory = OPENPBR_KERNEL_DIR;
    return settings;
}

// Every white, non-absorbing configuration renders at the environment's radiance within 1 %
// (mean over each sphere's fully covered pixels).
TEST(Render, FurnaceCpuWithinOnePercent)
{
    RenderSettings settings = quiet_settings();
    settings.furnace = true;
    settings.cell_size = 48;
    settings.samples_per_pixel = 128;
    settings.max_depth = 32;
    const std::vector<Material> materials = furnace_materials();
    const RenderImage image = render_materials(materials, settings, RenderBackend::cpu);
    EXPECT_EQ(image.nonfinite_samples, 0u);
    const std::vector<SphereStatistics> statistics = sphere_statistics(image, settings.environment);
    ASSERT_EQ(statistics.size(), materials.size());
    for (const SphereStatistics& entry : statistics)
    {
        EXPECT_GT(entry.pixels, 500u) << entry.label;
        EXPECT_LT(entry.relative_error, 0.01)
            << entry.label << ": " << entry.mean[0] << " " << entry.mean[1] << " " << entry.mean[2];
    }
    // The background is the environment itself.
    const std::size_t corner = 0;
    EXPECT_FLOAT_EQ(image.mean[corner], settings.environment);
}

// The same seeds give the same image: the random numbers depend only on (seed, pixel,
// sample, bounce, dimension), not on the schedule.
TEST(Render, CpuIsDeterministic)
{
    RenderSettings settings = quiet_settings();
    settings.cell_size = 16;
    settings.samples_per_pixel = 2;
    const std::vector<Material> materials = load_material_directory(OPENPBR_MATERIALS_DIR);
    const RenderImage a = render_materials(materials, settings, RenderBackend::cpu);
    settings.chunk_samples = 1;
    const RenderImage b = render_materials(materials, settings, RenderBackend::cpu);
    EXPECT_EQ(a.mean, b.mean);
    EXPECT_EQ(a.nonfinite_samples, 0u);
}

// Every bundled material on both backends with the same seeds: the difference is far below
// the Monte Carlo noise of one render, and no sample is non-finite on either.
TEST(Render, CpuMatchesVulkan)
{
    std::string reason;
    if (!vulkan_render_available(&reason))
    {
        GTEST_SKIP() << "no Vulkan device: " << reason;
    }
    ASSERT_TRUE(std::filesystem::exists(std::string(OPENPBR_KERNEL_DIR) + "/render.slang.spv"));
    RenderSettings settings = quiet_settings();
    settings.cell_size = 24;
    settings.samples_per_pixel = 8;
    const std::vector<Material> materials = load_material_directory(OPENPBR_MATERIALS_DIR);
    const RenderImage cpu = render_materials(materials, settings, RenderBackend::cpu);
    const RenderImage vulkan = render_materials(materials, settings, RenderBackend::vulkan);
    const RenderComparison comparison = compare_renders(cpu, vulkan);
    EXPECT_EQ(comparison.nonfinite_a, 0u);
    EXPECT_EQ(comparison.nonfinite_b, 0u);
    EXPECT_GT(comparison.noise, 0.0);
    EXPECT_LT(comparison.rmse, comparison.noise)
        << "identical pixels " << comparison.identical_fraction << ", max |diff| " << comparison.max_abs_difference;
    // Most paths make exactly the same decisions on both backends.
    EXPECT_GT(comparison.identical_fraction, 0.95);
    std::printf("[ render ] RMSE %.3g, noise %.3g, identical pixels %.2f %%, cpu %.0f ns, vulkan %.0f ns per "
                "pixel-sample\n",
                comparison.rmse, comparison.noise, 100.0 * comparison.identical_fraction, cpu.ns_per_pixel_sample,
                vulkan.ns_per_pixel_sample);
}

TEST(Render, LayoutOfTheGallery)
{
    RenderSettings settings = quiet_settings();
    settings.cell_size = 8;
    settings.samples_per_pixel = 1;
    const std::vector<Material> materials = load_material_directory(OPENPBR_MATERIALS_DIR);
    ASSERT_EQ(materials.size(), 55u);
    const RenderImage image = render_materials(materials, settings, RenderBackend::cpu);
    EXPECT_EQ(image.columns, 8);
    EXPECT_EQ(image.rows, 7);
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 56);
    EXPECT_EQ(image.labels.size(), 55u);
}

TEST(Render, WritesPngs)
{
    RenderSettings settings = quiet_settings();
    settings.furnace = true;
    settings.cell_size = 32;
    settings.samples_per_pixel = 1;
    const RenderImage image = render_materials(furnace_materials(), settings, RenderBackend::cpu);
    const std::filesystem::path directory = std::filesystem::temp_directory_path();
    const std::string path = (directory / "openpbr_test_render.png").string();
    const std::string difference = (directory / "openpbr_test_render_diff.png").string();
    write_render_png(path, image, 1.0f, true);
    write_difference_png(difference, image, image, 8.0f);
    EXPECT_GT(std::filesystem::file_size(path), 100u);
    EXPECT_GT(std::filesystem::file_size(difference), 50u);
    std::filesystem::remove(path);
    std::filesystem::remove(difference);
}

TEST(RenderFont, WidthAndWrapping)
{
    EXPECT_EQ(font::text_width("", 1), 0);
    EXPECT_EQ(font::text_width("A", 1), 5);
    EXPECT_EQ(font::text_width("AB", 2), 22);
    const std::vector<std::string> lines = font::wrap_text("Honey_crystallized", 60, 1);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], "Honey");
    EXPECT_EQ(lines[1], "crystalliz");  // cut to the 10 characters a 60-pixel line holds
    EXPECT_EQ(font::wrap_text("a b c", 100, 1), std::vector<std::string>{"a b c"});
}

}  // namespace
