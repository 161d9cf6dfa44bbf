// Preview path tracer: white furnace on the CPU backend, CPU versus Vulkan on the same seeds,
// determinism, nested media on both backends (index-matched interfaces invisible, nested white
// dielectrics in the furnace, cells the medium stack cannot hold rejected), and the label font.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <ostream>
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

// ---- Nested media (targets/kernels/openpbr_render_kernel.h) ----------------------------------

// A smooth, non-dispersive dielectric: delta interfaces, so the Fresnel choice is exact at
// every relative IOR (1 included) and the tests below see only the medium tracking.
Material smooth_dielectric(const std::string& name, float ior)
{
    Material material = default_material();
    material.name = name;
    material.inputs.transmission_weight = 1.0f;
    material.inputs.specular_roughness = 0.0f;
    material.inputs.specular_ior = ior;
    material.inputs.base_color = glm::vec3(1.0f);
    material.inputs.specular_color = glm::vec3(1.0f);
    material.inputs.transmission_color = glm::vec3(1.0f);
    return material;
}

RenderObject sphere_of(const Material& material, float radius, float x = 0.0f, float y = 0.0f, float z = 0.0f)
{
    RenderObject object;
    object.material = material;
    object.radius = radius;
    object.center[0] = x;
    object.center[1] = y;
    object.center[2] = z;
    return object;
}

}  // namespace

namespace openpbr::host {
// GoogleTest prints the parameter by this name in test listings (ctest shows it).
void PrintTo(RenderBackend backend, std::ostream* stream) { *stream << to_string(backend); }
}  // namespace openpbr::host

namespace {

class NestedMedia : public ::testing::TestWithParam<RenderBackend>
{
  protected:
    void SetUp() override
    {
        std::string reason;
        if (GetParam() == RenderBackend::vulkan && !vulkan_render_available(&reason))
        {
            GTEST_SKIP() << "no Vulkan device: " << reason;
        }
    }

    // The cells in one row (one render: lavapipe compiles the kernel once per render). The
    // same cell position in two such renders sees the same pixel keys, hence the same seeds.
    RenderImage render_row(const std::vector<RenderCell>& cells, bool furnace) const
    {
        RenderSettings settings = quiet_settings();
        settings.furnace = furnace;
        settings.area_light = false;  // sky and ground: smooth light, no fireflies
        settings.cell_size = 32;
        settings.columns = int(cells.size());
        settings.samples_per_pixel = 128;
        settings.max_depth = 64;
        return render_cells(cells, settings, GetParam());
    }
};

// The pixels of one cell of a one-row render, as an image of their own.
RenderImage cell_of(const RenderImage& image, int cell)
{
    RenderImage out;
    out.width = image.cell_size;
    out.height = image.cell_size;
    out.cell_size = image.cell_size;
    out.columns = 1;
    out.rows = 1;
    out.samples_per_pixel = image.samples_per_pixel;
    out.labels = {image.labels[std::size_t(cell)]};
    for (int y = 0; y < image.cell_size; ++y)
    {
        for (int x = cell * image.cell_size; x < (cell + 1) * image.cell_size; ++x)
        {
            const std::size_t pixel = std::size_t(y) * std::size_t(image.width) + std::size_t(x);
            for (std::size_t channel = 0; channel < 3; ++channel)
            {
                out.mean.push_back(image.mean[pixel * 3 + channel]);
                out.variance_of_mean.push_back(image.variance_of_mean[pixel * 3 + channel]);
            }
            out.object_fraction.push_back(image.object_fraction[pixel]);
        }
    }
    return out;
}

// An interface between two media of equal IOR is no interface: a glass sphere holding a
// sphere of the same glass renders like the glass alone, and an air sphere of lower priority
// poking out of a water sphere renders like the water alone (inside the water its surface is a
// false hit, outside it separates air from air). Lit by the sky over the checkered ground,
// where a wrong exterior IOR shows as a refracting inner sphere. The same comparison sees a
// real interface: an air bubble in water against the water alone.
TEST_P(NestedMedia, IndexMatchedInterfacesAreInvisible)
{
    const Material glass = smooth_dielectric("glass", 1.5f);
    const Material water = smooth_dielectric("water", 1.33f);
    const Material air = smooth_dielectric("air", 1.0f);
    const std::vector<RenderCell> scenes = {
        {"glass in glass", {sphere_of(glass, 1.0f), sphere_of(glass, 0.6f, 0.1f, 0.1f, 0.2f)}},
        {"air under water", {sphere_of(air, 0.6f, 0.0f, 0.0f, 0.6f), sphere_of(water, 1.0f)}},
        {"air bubble in water", {sphere_of(water, 1.0f), sphere_of(air, 0.45f, 0.2f, 0.15f, 0.3f)}},
    };
    const std::vector<RenderCell> references = {
        {"glass", {sphere_of(glass, 1.0f)}},
        {"water", {sphere_of(water, 1.0f)}},
        {"water", {sphere_of(water, 1.0f)}},
    };
    const RenderImage scene_image = render_row(scenes, false);
    const RenderImage reference_image = render_row(references, false);
    EXPECT_EQ(scene_image.nonfinite_samples + reference_image.nonfinite_samples, 0u);
    for (int cell = 0; cell < int(scenes.size()); ++cell)
    {
        const RenderComparison comparison = compare_renders(cell_of(scene_image, cell), cell_of(reference_image, cell));
        const double ratio = comparison.rmse / comparison.noise;
        const std::string& name = scenes[std::size_t(cell)].label;
        std::printf("[ nested ] %s against %s (%s): RMSE %.4g, noise %.4g, ratio %.3f\n", name.c_str(),
                    references[std::size_t(cell)].label.c_str(), to_string(GetParam()), comparison.rmse, comparison.noise,
                    ratio);
        if (name == "air bubble in water")
        {
            EXPECT_GT(ratio, 2.0) << name;  // measured 3.7 (CPU and lavapipe)
        }
        else
        {
            // Two renders of one expectation differ by sqrt(2) x noise when independent, less
            // when their paths agree up to the hidden interface (measured 0.85 and 0.83, CPU and
            // lavapipe, 128 spp). Measured with the tracking broken: 5.3 (glass in glass with
            // exterior IOR 1) and 5.2 (air under water without the false-hit rule).
            EXPECT_LT(ratio, 1.5) << name;
        }
    }
}

// Mean over the fully covered pixels of one cell of a furnace render, and its standard error
// (the pixels' means are independent).
struct FurnaceMean
{
    double mean = 0.0;
    double standard_error = 0.0;
};

FurnaceMean furnace_mean(const RenderImage& image, int cell)
{
    const RenderImage one = cell_of(image, cell);
    const SphereStatistics statistics = sphere_statistics(one, 1.0f).front();
    double variance = 0.0;
    for (std::size_t pixel = 0; pixel < one.object_fraction.size(); ++pixel)
    {
        if (one.object_fraction[pixel] < 1.0f) continue;
        variance += one.variance_of_mean[pixel * 3];
    }
    EXPECT_GT(statistics.pixels, 300u);
    // White materials: the three channels are the same paths, so the red one stands for all.
    return {statistics.mean[0], std::sqrt(variance) / double(statistics.pixels)};
}

// The white nested scenes: the gallery's glass of water and air bubble in water, and a glass
// ball in water, all white and non-absorbing, with every interface at `roughness`.
std::vector<RenderCell> white_nested_cells(float roughness)
{
    const Material glass = smooth_dielectric("glass", 1.52f);
    const Material water = smooth_dielectric("water", 1.33f);
    std::vector<RenderCell> cells = nested_media_cells(glass, true);
    cells.push_back({"Glass in water", {sphere_of(water, 1.0f), sphere_of(glass, 0.5f, -0.2f, 0.0f, 0.3f)}});
    for (RenderCell& cell : cells)
    {
        cell.label += roughness > 0.0f ? " (rough)" : "";
        for (RenderObject& object : cell.objects) object.material.inputs.specular_roughness = roughness;
    }
    return cells;
}

// White furnace of the nested white dielectrics, smooth and rough (one render).
// Smooth: the sampled Fresnel choice makes every weight 1, so a path returns exactly 1 unless
// the depth cap (64 surface events) ends it. Measured (CPU and lavapipe, 128 spp, 32-pixel
// cells): glass of water 1.00000, air bubble in water 0.99950 (standard error 1.1e-4: paths
// trapped between the bubble and the water's surface reach the cap), glass in water 0.99995.
// Bounds: a loss of at most 0.2 % (four times the largest measured).
// Rough (roughness 0.2): below relative IOR 1 (water seen from glass 0.875, air seen from water
// 0.75) the few transmitting microfacets carry large sample weights (docs/known-limits.md), so
// these estimates are noisy. Measured: glass of water 1.0071 +- 0.014, air bubble in water
// 0.9984 +- 0.0015, glass in water (relative IOR 1.14) 0.99996 +- 0.00055 (they were 0.9688 and
// 0.9719 before the light the transmission compensation's floor keeps went to reflection).
// Bound: the sweep's 0.99 within 3 standard errors.
// Both: no gain beyond 3 standard errors (plus 1e-6 for float sums).
TEST_P(NestedMedia, FurnaceKeepsEnergy)
{
    std::vector<RenderCell> cells = white_nested_cells(0.0f);
    const std::size_t smooth_count = cells.size();
    const std::vector<RenderCell> rough = white_nested_cells(0.2f);
    cells.insert(cells.end(), rough.begin(), rough.end());
    const RenderImage image = render_row(cells, true);
    EXPECT_EQ(image.nonfinite_samples, 0u);
    for (std::size_t cell = 0; cell < cells.size(); ++cell)
    {
        const FurnaceMean result = furnace_mean(image, int(cell));
        const std::string& name = cells[cell].label;
        std::printf("[ nested ] furnace %s (%s): %.5f, standard error %.2g\n", name.c_str(), to_string(GetParam()),
                    result.mean, result.standard_error);
        EXPECT_LE(result.mean, 1.0 + 3.0 * result.standard_error + 1e-6) << name;
        if (cell < smooth_count)
        {
            EXPECT_GE(result.mean, 0.998) << name;
        }
        else
        {
            EXPECT_GE(result.mean + 3.0 * result.standard_error, 0.99) << name;
        }
    }
}

// A cell the medium stack cannot hold, and objects the kernel cannot place, are errors.
TEST(NestedMediaScene, RejectsCellsTheKernelCannotRender)
{
    RenderSettings settings = quiet_settings();
    settings.cell_size = 8;
    settings.samples_per_pixel = 1;
    const Material glass = smooth_dielectric("glass", 1.5f);
    const std::vector<RenderCell> bad_cells = {
        {"empty", {}},
        {"five objects", std::vector<RenderObject>(std::size_t(kRenderMaxObjects) + 1, sphere_of(glass, 0.5f))},
        {"below the ground", {sphere_of(glass, 0.5f, 0.0f, -0.6f, 0.0f)}},
        {"zero radius", {sphere_of(glass, 0.0f)}},
        {"not finite", {sphere_of(glass, 0.5f, std::nanf(""), 0.0f, 0.0f)}},
    };
    for (const RenderCell& cell : bad_cells)
    {
        EXPECT_THROW(render_cells({cell}, settings, RenderBackend::cpu), std::invalid_argument) << cell.label;
    }
    const std::vector<RenderObject> full(std::size_t(kRenderMaxObjects), sphere_of(glass, 0.5f));
    const RenderImage image = render_cells({{"four objects", full}}, settings, RenderBackend::cpu);
    EXPECT_EQ(image.nonfinite_samples, 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, NestedMedia, ::testing::Values(RenderBackend::cpu, RenderBackend::vulkan),
                         [](const ::testing::TestParamInfo<RenderBackend>& info) {
                             return std::string(to_string(info.param));
                         });

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
