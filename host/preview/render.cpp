// Preview path tracer: scene setup, the CPU and Vulkan backends, statistics; see render.h.
#include "host/preview/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "host/scene/colour_spaces.h"
#include "host/scene/material_packing.h"
#include "host/gpu/shipped_tables.h"
#include "host/gpu/vulkan_runner.h"
#include "host/support/progress.h"
#include "host/support/stopwatch.h"
#include "slang/openpbr.h"

// The CPU build of the shared kernel body: the macros read the buffers the renderer points
// these at before each pass (read-only except the accumulation, where each pixel writes only
// its own record). One CPU render at a time (render_mutex).
namespace openpbr::host::render_kernel {
const std::uint32_t* parameters = nullptr;
const float* scene = nullptr;
const float* materials = nullptr;
float* accumulation = nullptr;
}  // namespace openpbr::host::render_kernel
#define OPENPBR_RENDER_PARAMETER(index) ::openpbr::host::render_kernel::parameters[index]
#define OPENPBR_RENDER_SCENE(index) ::openpbr::host::render_kernel::scene[index]
#define OPENPBR_RENDER_MATERIAL(index) ::openpbr::host::render_kernel::materials[index]
#define OPENPBR_RENDER_ACCUMULATION_READ(index) ::openpbr::host::render_kernel::accumulation[index]
#define OPENPBR_RENDER_ACCUMULATION_WRITE(index, value) ::openpbr::host::render_kernel::accumulation[index] = (value)
#include "targets/kernels/openpbr_render_kernel.h"

static_assert(OPENPBR_RENDER_LOBE_TYPE_SPECULAR == OPENPBR_LOBE_TYPE_SPECULAR, "kernel copy of a library constant");
static_assert(OPENPBR_RENDER_FLOAT_MAX == OPENPBR_FLOAT_MAX, "kernel copy of a library constant");
static_assert(OPENPBR_RENDER_TWO_PI == OPENPBR_TWO_PI, "kernel copy of a library constant");
static_assert(openpbr::host::kRenderMaxObjects == int(OPENPBR_RENDER_MAX_OBJECTS), "host copy of a kernel constant");

namespace openpbr::host {

namespace {

std::mutex render_mutex;

// ---- Scene -----------------------------------------------------------------------------------

struct Vec3
{
    float x, y, z;
};

Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3 normalized(Vec3 a)
{
    const float length = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return a * (1.0f / length);
}

void put3(std::vector<float>& scene, int index, Vec3 value)
{
    scene[std::size_t(index)] = value.x;
    scene[std::size_t(index) + 1] = value.y;
    scene[std::size_t(index) + 2] = value.z;
}

// A colour of the scene given in linear Rec.709, stored in the working space (docs/colour.md).
void put_rec709(std::vector<float>& scene, int index, glm::vec3 rec709)
{
    const glm::vec3 working = rec709_to_working_space(rec709);
    put3(scene, index, {working.x, working.y, working.z});
}

struct Layout
{
    int columns = 1;
    int rows = 1;
    int cell = 1;
    int width = 1;
    int height = 1;
};

Layout make_layout(std::size_t material_count, const RenderSettings& settings)
{
    if (material_count == 0) throw std::invalid_argument("render: nothing to render (no materials or cells)");
    if (settings.cell_size < 8 || settings.cell_size > 4096)
    {
        throw std::invalid_argument("render: cell size must be in [8, 4096], got " + std::to_string(settings.cell_size));
    }
    Layout layout;
    layout.columns =
        settings.columns > 0 ? settings.columns : std::max(1, int(std::ceil(std::sqrt(double(material_count)) - 1e-9)));
    layout.columns = std::min<int>(layout.columns, int(material_count));
    layout.rows = int((material_count + std::size_t(layout.columns) - 1) / std::size_t(layout.columns));
    layout.cell = settings.cell_size;
    layout.width = layout.columns * layout.cell;
    layout.height = layout.rows * layout.cell;
    return layout;
}

std::vector<std::uint32_t> make_parameters(const Layout& layout, std::size_t cell_count, std::size_t material_count,
                                           const RenderSettings& settings)
{
    std::vector<std::uint32_t> parameters(OPENPBR_RENDER_PARAMETER_COUNT, 0u);
    parameters[OPENPBR_RENDER_PARAMETER_WIDTH] = std::uint32_t(layout.width);
    parameters[OPENPBR_RENDER_PARAMETER_HEIGHT] = std::uint32_t(layout.height);
    parameters[OPENPBR_RENDER_PARAMETER_SEED] = settings.seed;
    parameters[OPENPBR_RENDER_PARAMETER_CELL_SIZE] = std::uint32_t(layout.cell);
    parameters[OPENPBR_RENDER_PARAMETER_COLUMNS] = std::uint32_t(layout.columns);
    parameters[OPENPBR_RENDER_PARAMETER_CELL_COUNT] = std::uint32_t(cell_count);
    parameters[OPENPBR_RENDER_PARAMETER_GROUND_MATERIAL] = std::uint32_t(material_count);
    parameters[OPENPBR_RENDER_PARAMETER_FLAGS] = settings.furnace ? 0u
                                                                  : (OPENPBR_RENDER_FLAG_GROUND | OPENPBR_RENDER_FLAG_SKY |
                                                                     (settings.area_light ? OPENPBR_RENDER_FLAG_LIGHT : 0u));
    parameters[OPENPBR_RENDER_PARAMETER_MAX_DEPTH] = std::uint32_t(std::max(settings.max_depth, 1));
    parameters[OPENPBR_RENDER_PARAMETER_MAX_VOLUME_EVENTS] = std::uint32_t(std::max(settings.max_volume_events, 0));
    parameters[OPENPBR_RENDER_PARAMETER_RR_DEPTH] = std::uint32_t(std::max(settings.roulette_depth, 1));
    return parameters;
}

void check_cell(const RenderCell& cell)
{
    const std::string where = "render: cell '" + cell.label + "': ";
    if (cell.objects.empty()) throw std::invalid_argument(where + "no objects");
    if (cell.objects.size() > std::size_t(kRenderMaxObjects))
    {
        throw std::invalid_argument(where + std::to_string(cell.objects.size()) + " objects, at most " +
                                    std::to_string(kRenderMaxObjects) + " (the medium stack has one bit per object)");
    }
    for (const RenderObject& object : cell.objects)
    {
        const bool finite = std::isfinite(object.center[0]) && std::isfinite(object.center[1]) &&
                            std::isfinite(object.center[2]) && std::isfinite(object.radius);
        if (!finite || !(object.radius > 0.0f))
        {
            throw std::invalid_argument(where + "object '" + object.material.name +
                                        "' needs a finite center and a radius > 0");
        }
        // The kernel does not look for the ground from inside an object.
        if (object.center[1] - object.radius < -1.0f - 1e-6f)
        {
            throw std::invalid_argument(where + "object '" + object.material.name + "' reaches below the ground (y = -1)");
        }
    }
}

// The cell scene: the cell's objects (a unit sphere at the origin for a plain cell) on the
// ground y = -1, camera in front and a little above, the area light up and to the left, a
// gradient sky with a warm glow round the light. Then the object records of every cell
// (targets/kernels/openpbr_render_kernel.h), the k-th object overall carrying packed material k.
std::vector<float> make_scene(const RenderSettings& settings, const std::vector<RenderCell>& cells)
{
    std::vector<float> scene(
        OPENPBR_RENDER_SCENE_COUNT + cells.size() * OPENPBR_RENDER_MAX_OBJECTS * OPENPBR_RENDER_OBJECT_FLOATS, 0.0f);
    const Vec3 camera = {0.0f, 0.7f, 4.5f};
    const Vec3 target = {0.0f, -0.1f, 0.0f};
    const float tan_half_fov = 0.34f;  // the sphere fills about 70 % of the cell's height
    const Vec3 forward = normalized(target - camera);
    const Vec3 right = normalized(cross(forward, {0.0f, 1.0f, 0.0f}));
    const Vec3 up = cross(right, forward);
    put3(scene, OPENPBR_RENDER_SCENE_CAMERA_POSITION, camera);
    put3(scene, OPENPBR_RENDER_SCENE_CAMERA_FORWARD, forward);
    put3(scene, OPENPBR_RENDER_SCENE_CAMERA_RIGHT, right * tan_half_fov);
    put3(scene, OPENPBR_RENDER_SCENE_CAMERA_UP, up * tan_half_fov);
    scene[OPENPBR_RENDER_SCENE_SPHERE_RADIUS] = 1.0f;
    const Vec3 light = {-3.5f, 5.5f, 3.5f};
    put3(scene, OPENPBR_RENDER_SCENE_LIGHT_CENTER, light);
    scene[OPENPBR_RENDER_SCENE_LIGHT_RADIUS] = 1.0f;
    // The light and sky colours are linear Rec.709 (viewer/src/scene.mjs converts the same).
    put_rec709(scene, OPENPBR_RENDER_SCENE_LIGHT_RADIANCE, {40.0f, 38.0f, 34.0f});
    put_rec709(scene, OPENPBR_RENDER_SCENE_SKY_ZENITH, {0.16f, 0.26f, 0.5f});
    put_rec709(scene, OPENPBR_RENDER_SCENE_SKY_HORIZON, {0.7f, 0.75f, 0.85f});
    const float environment = settings.environment;
    put3(scene, OPENPBR_RENDER_SCENE_ENVIRONMENT,
         settings.furnace ? Vec3{environment, environment, environment} : Vec3{0.2f, 0.2f, 0.2f});
    put3(scene, OPENPBR_RENDER_SCENE_SUN_DIRECTION, normalized(light));
    put_rec709(scene, OPENPBR_RENDER_SCENE_SUN_GLOW, {0.6f, 0.45f, 0.25f});
    scene[OPENPBR_RENDER_SCENE_SUN_EXPONENT] = 12.0f;
    scene[OPENPBR_RENDER_SCENE_NITS_TO_UNITS] = kNitsToRenderUnits;
    scene[OPENPBR_RENDER_SCENE_CHECKER_SIZE] = 0.5f;
    scene[OPENPBR_RENDER_SCENE_CHECKER_DARK] = 0.55f;
    const glm::vec3 wavelengths = OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM;
    put3(scene, OPENPBR_RENDER_SCENE_DEFAULT_WAVELENGTHS, {wavelengths.x, wavelengths.y, wavelengths.z});
    std::size_t material_index = 0;
    for (std::size_t cell = 0; cell < cells.size(); ++cell)
    {
        for (std::size_t slot = 0; slot < cells[cell].objects.size(); ++slot)
        {
            const RenderObject& object = cells[cell].objects[slot];
            const int record =
                int(OPENPBR_RENDER_SCENE_COUNT + (cell * OPENPBR_RENDER_MAX_OBJECTS + slot) * OPENPBR_RENDER_OBJECT_FLOATS);
            const OpenPBR_ResolvedInputs& inputs = object.material.inputs;
            // The medium's IOR and volume as the BSDF sees them: after the input contract.
            const OpenPBR_ResolvedInputs contracted = openpbr_prepare_inputs(inputs);
            const OpenPBR_HomogeneousVolume volume = openpbr_prepare_volume(inputs);
            put3(scene, record + int(OPENPBR_RENDER_OBJECT_CENTER), {object.center[0], object.center[1], object.center[2]});
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_RADIUS] = object.radius;
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_MATERIAL] = float(material_index++);
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_MEDIUM_IOR] = contracted.specular_ior;
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_ENCLOSES] = inputs.geometry_thin_walled ? 0.0f : 1.0f;
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_DISPERSIVE] =
                openpbr_needs_rgb_wavelengths(inputs) ? 1.0f : 0.0f;
            put3(scene, record + int(OPENPBR_RENDER_OBJECT_EXTINCTION),
                 {volume.extinction.x, volume.extinction.y, volume.extinction.z});
            put3(scene, record + int(OPENPBR_RENDER_OBJECT_ALBEDO), {volume.albedo.x, volume.albedo.y, volume.albedo.z});
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_ANISOTROPY] = volume.anisotropy;
            scene[std::size_t(record) + OPENPBR_RENDER_OBJECT_VOLUME_PRESENT] = volume.is_present ? 1.0f : 0.0f;
        }
    }
    return scene;
}

// ---- Shared pieces of both backends --------------------------------------------------------

struct PreparedRender
{
    Layout layout;
    std::vector<std::uint32_t> parameters;
    std::vector<float> scene;
    std::vector<float> materials;  // packed; the ground last
    std::vector<std::string> labels;
    std::size_t pixel_count = 0;
};

PreparedRender prepare_render(const std::vector<RenderCell>& cells, const RenderSettings& settings)
{
    if (settings.samples_per_pixel < 1) throw std::invalid_argument("render: samples per pixel must be >= 1");
    for (const RenderCell& cell : cells) check_cell(cell);
    PreparedRender prepared;
    std::vector<Material> packed;
    for (const RenderCell& cell : cells)
    {
        for (const RenderObject& object : cell.objects) packed.push_back(object.material);
    }
    prepared.layout = make_layout(cells.size(), settings);
    prepared.parameters = make_parameters(prepared.layout, cells.size(), packed.size(), settings);
    prepared.scene = make_scene(settings, cells);
    packed.push_back(render_ground_material());
    prepared.materials = pack_materials(packed);
    for (const RenderCell& cell : cells) prepared.labels.push_back(cell.label);
    prepared.pixel_count = std::size_t(prepared.layout.width) * std::size_t(prepared.layout.height);
    return prepared;
}

RenderImage finish_image(const PreparedRender& prepared, const std::vector<float>& accumulation,
                         const RenderSettings& settings)
{
    RenderImage image;
    image.width = prepared.layout.width;
    image.height = prepared.layout.height;
    image.cell_size = prepared.layout.cell;
    image.columns = prepared.layout.columns;
    image.rows = prepared.layout.rows;
    image.samples_per_pixel = settings.samples_per_pixel;
    image.labels = prepared.labels;
    image.mean.assign(prepared.pixel_count * 3, 0.0f);
    image.variance_of_mean.assign(prepared.pixel_count * 3, 0.0f);
    image.object_fraction.assign(prepared.pixel_count, 0.0f);
    const double n = double(settings.samples_per_pixel);
    for (std::size_t pixel = 0; pixel < prepared.pixel_count; ++pixel)
    {
        const float* record = accumulation.data() + pixel * OPENPBR_RENDER_ACCUMULATION_FLOATS;
        for (int channel = 0; channel < 3; ++channel)
        {
            const double mean = double(record[channel]) / n;
            const double mean_square = double(record[3 + channel]) / n;
            // Unbiased sample variance, divided by n for the variance of the mean.
            const double variance = n > 1.0 ? std::max(0.0, (mean_square - mean * mean) * n / (n - 1.0)) : 0.0;
            image.mean[pixel * 3 + std::size_t(channel)] = float(mean);
            image.variance_of_mean[pixel * 3 + std::size_t(channel)] = float(variance / n);
        }
        image.nonfinite_samples += std::uint64_t(record[6]);
        image.object_fraction[pixel] = float(double(record[7]) / n);
    }
    return image;
}

int automatic_chunk(int samples_per_pixel)
{
    // About 16 passes: frequent progress, negligible per-pass overhead.
    return std::max(1, samples_per_pixel / 16);
}

RenderImage render_cpu(const std::vector<RenderCell>& cells, const RenderSettings& settings)
{
    const Stopwatch total_stopwatch;
    PreparedRender prepared = prepare_render(cells, settings);
    std::vector<float> accumulation(prepared.pixel_count * OPENPBR_RENDER_ACCUMULATION_FLOATS, 0.0f);
    const int threads = tbb::this_task_arena::max_concurrency();

    std::lock_guard<std::mutex> lock(render_mutex);
    render_kernel::parameters = prepared.parameters.data();
    render_kernel::scene = prepared.scene.data();
    render_kernel::materials = prepared.materials.data();
    render_kernel::accumulation = accumulation.data();

    const int spp = settings.samples_per_pixel;
    const int chunk = settings.chunk_samples > 0 ? settings.chunk_samples : automatic_chunk(spp);
    ProgressReporter progress(std::uint64_t(spp), settings.progress,
                              settings.progress_label.empty() ? "cpu" : settings.progress_label);
    const Stopwatch render_stopwatch;
    double first_pass = 0.0;
    for (int begin = 0; begin < spp; begin += chunk)
    {
        const Stopwatch pass_stopwatch;
        const int end = std::min(spp, begin + chunk);
        prepared.parameters[OPENPBR_RENDER_PARAMETER_SAMPLE_BEGIN] = std::uint32_t(begin);
        prepared.parameters[OPENPBR_RENDER_PARAMETER_SAMPLE_END] = std::uint32_t(end);
        const tbb::blocked_range2d<int> range(0, prepared.layout.height, 8, 0, prepared.layout.width, 8);
        tbb::parallel_for(range, [](const tbb::blocked_range2d<int>& block) {
            for (int y = block.rows().begin(); y < block.rows().end(); ++y)
            {
                for (int x = block.cols().begin(); x < block.cols().end(); ++x)
                {
                    openpbr::openpbr_render_pixel(unsigned(x), unsigned(y));
                }
            }
        });
        if (begin == 0) first_pass = pass_stopwatch.seconds();
        progress.set_done(std::uint64_t(end));
    }
    progress.finish();
    const double render_seconds = render_stopwatch.seconds();
    render_kernel::accumulation = nullptr;

    RenderImage image = finish_image(prepared, accumulation, settings);
    image.seconds = total_stopwatch.seconds();
    image.first_pass_seconds = first_pass;
    image.ns_per_pixel_sample = render_seconds * 1e9 / (double(prepared.pixel_count) * double(spp));
    image.device = std::to_string(threads) + " TBB threads";
    return image;
}

RenderImage render_vulkan(const std::vector<RenderCell>& cells, const RenderSettings& settings)
{
    const Stopwatch total_stopwatch;
    PreparedRender prepared = prepare_render(cells, settings);
    std::string error;
    std::optional<VulkanContext> context = VulkanContext::create(VulkanOptions{}, &error);
    if (!context) throw std::runtime_error("render: no Vulkan device: " + error);

    ComputePipelineDescription description;
    const std::string kernel_path = settings.kernel_directory + "/render.slang.spv";
    description.spirv_words = load_spirv_file(kernel_path);
    description.entry_point = "main";
    description.bindings = {{0, false}, {1, false}, {2, false}, {3, false}, {4, false}, {5, false}};
    ComputePipeline pipeline(*context, description);

    std::vector<std::byte> lut_bytes = to_bytes(shipped_lut());
    std::vector<std::byte> fuzz_bytes = to_bytes(shipped_fuzz_ltc());
    std::vector<std::byte> scene_bytes = to_bytes(prepared.scene);
    std::vector<std::byte> material_bytes = to_bytes(prepared.materials);
    std::vector<std::byte> accumulation_bytes(prepared.pixel_count * OPENPBR_RENDER_ACCUMULATION_FLOATS * sizeof(float),
                                              std::byte{0});
    const std::uint32_t groups_x = std::uint32_t((prepared.layout.width + 7) / 8);
    const std::uint32_t groups_y = std::uint32_t((prepared.layout.height + 7) / 8);

    const int spp = settings.samples_per_pixel;
    ProgressReporter progress(std::uint64_t(spp), settings.progress,
                              settings.progress_label.empty() ? "vulkan" : settings.progress_label);
    const Stopwatch render_stopwatch;
    double first_pass = 0.0;
    double steady_seconds = 0.0;
    int steady_samples = 0;
    int chunk = settings.chunk_samples > 0 ? settings.chunk_samples : 1;
    for (int begin = 0; begin < spp;)
    {
        const int end = std::min(spp, begin + chunk);
        prepared.parameters[OPENPBR_RENDER_PARAMETER_SAMPLE_BEGIN] = std::uint32_t(begin);
        prepared.parameters[OPENPBR_RENDER_PARAMETER_SAMPLE_END] = std::uint32_t(end);
        std::vector<std::byte> parameter_bytes = to_bytes(prepared.parameters);
        const std::vector<BufferBinding> buffers = {{0, &lut_bytes, false},       {1, &fuzz_bytes, false},
                                                    {2, &parameter_bytes, false}, {3, &scene_bytes, false},
                                                    {4, &material_bytes, false},  {5, &accumulation_bytes, true}};
        const Stopwatch pass_stopwatch;
        run(pipeline, buffers, groups_x, groups_y, 1, 1);
        const double pass_seconds = pass_stopwatch.seconds();
        if (begin == 0)
        {
            first_pass = pass_seconds;
        }
        else
        {
            steady_seconds += pass_seconds;
            steady_samples += end - begin;
        }
        progress.set_done(std::uint64_t(end));
        begin = end;
        if (settings.chunk_samples <= 0 && begin > 1)
        {
            // About two seconds per dispatch, from the passes after the first (which compiles).
            const double per_sample = steady_samples > 0 ? steady_seconds / steady_samples : pass_seconds;
            chunk = std::clamp(int(2.0 / std::max(per_sample, 1e-6)), 1, std::max(1, spp / 8));
        }
        else if (settings.chunk_samples <= 0)
        {
            chunk = 1;  // the second pass measures the steady-state speed
        }
    }
    progress.finish();
    const double render_seconds = render_stopwatch.seconds();

    RenderImage image = finish_image(prepared, from_bytes<float>(accumulation_bytes), settings);
    image.seconds = total_stopwatch.seconds();
    image.first_pass_seconds = first_pass;
    // Steady state: the passes after the first (lavapipe compiles the shader at the first).
    const double per_sample = steady_samples > 0 ? steady_seconds / steady_samples : render_seconds / spp;
    image.ns_per_pixel_sample = per_sample * 1e9 / double(prepared.pixel_count);
    image.device = context->device_name();
    return image;
}

}  // namespace

const char* to_string(RenderBackend backend) { return backend == RenderBackend::cpu ? "cpu" : "vulkan"; }

bool vulkan_render_available(std::string* reason)
{
    std::string error;
    const std::optional<VulkanContext> context = VulkanContext::create(VulkanOptions{}, &error);
    if (!context && reason) *reason = error;
    return context.has_value();
}

RenderImage render_cells(const std::vector<RenderCell>& cells, const RenderSettings& settings, RenderBackend backend)
{
    return backend == RenderBackend::cpu ? render_cpu(cells, settings) : render_vulkan(cells, settings);
}

std::vector<RenderCell> material_cells(const std::vector<Material>& materials)
{
    std::vector<RenderCell> cells;
    cells.reserve(materials.size());
    for (const Material& material : materials)
    {
        RenderObject sphere;
        sphere.material = material;
        cells.push_back({material.name, {sphere}});
    }
    return cells;
}

RenderImage render_materials(const std::vector<Material>& materials, const RenderSettings& settings, RenderBackend backend)
{
    return render_cells(material_cells(materials), settings, backend);
}

Material water_material(bool white)
{
    Material water = default_material();
    water.name = white ? "White water" : "Water";
    water.inputs.transmission_weight = 1.0f;
    water.inputs.specular_roughness = 0.0f;
    water.inputs.specular_ior = 1.33f;
    water.inputs.base_color = glm::vec3(1.0f);
    water.inputs.specular_color = glm::vec3(1.0f);
    water.inputs.transmission_color = white ? glm::vec3(1.0f) : glm::vec3(0.86f, 0.96f, 0.97f);
    water.inputs.transmission_depth = white ? 0.0f : 2.0f;
    return water;
}

Material air_material()
{
    Material air = default_material();
    air.name = "Air";
    air.inputs.transmission_weight = 1.0f;
    air.inputs.specular_roughness = 0.0f;
    air.inputs.specular_ior = 1.0f;
    air.inputs.base_color = glm::vec3(1.0f);
    air.inputs.specular_color = glm::vec3(1.0f);
    air.inputs.transmission_color = glm::vec3(1.0f);
    return air;
}

std::vector<RenderCell> nested_media_cells(const Material& glass, bool white)
{
    const Material water = water_material(white);
    RenderObject glass_shell;
    glass_shell.material = glass;
    if (white)
    {
        glass_shell.material.name = "White " + glass.name;
        glass_shell.material.inputs.base_color = glm::vec3(1.0f);
        glass_shell.material.inputs.specular_color = glm::vec3(1.0f);
        glass_shell.material.inputs.transmission_color = glm::vec3(1.0f);
        // Dispersion keeps the energy but spreads it over the channels' paths: in a furnace it
        // is color noise (about 1 % per channel at 1024 spp for the bundled Glass alone).
        glass_shell.material.inputs.transmission_dispersion_scale = 0.0f;
    }
    RenderObject water_inside;
    water_inside.material = water;
    water_inside.radius = 0.9f;  // a glass wall 0.1 thick
    RenderObject water_sphere;
    water_sphere.material = water;
    RenderObject bubble;
    bubble.material = air_material();
    bubble.radius = 0.45f;
    // Up, right and towards the camera: the bubble overlaps the sphere's middle only partly.
    bubble.center[0] = 0.2f;
    bubble.center[1] = 0.15f;
    bubble.center[2] = 0.3f;
    return {{"Glass of water", {glass_shell, water_inside}}, {"Air bubble in water", {water_sphere, bubble}}};
}

Material render_ground_material()
{
    Material ground = default_material();
    ground.name = "Ground";
    ground.inputs.base_color = glm::vec3(0.5f);
    ground.inputs.specular_roughness = 0.6f;
    return ground;
}

std::vector<Material> furnace_materials()
{
    std::vector<Material> materials;
    auto white = [&](const std::string& name) -> OpenPBR_ResolvedInputs& {
        Material material = default_material();
        material.name = name;
        material.inputs.base_color = glm::vec3(1.0f);
        material.inputs.specular_color = glm::vec3(1.0f);
        material.inputs.subsurface_color = glm::vec3(1.0f);
        material.inputs.transmission_color = glm::vec3(1.0f);
        materials.push_back(material);
        return materials.back().inputs;
    };
    white("Diffuse + specular");
    OpenPBR_ResolvedInputs& metal = white("Metal");
    metal.base_metalness = 1.0f;
    OpenPBR_ResolvedInputs& glass = white("Glass");
    glass.transmission_weight = 1.0f;
    glass.specular_roughness = 0.0f;
    OpenPBR_ResolvedInputs& coat = white("Coat over white");
    coat.coat_weight = 1.0f;
    coat.coat_roughness = 0.1f;
    OpenPBR_ResolvedInputs& fuzz = white("Fuzz over white");
    fuzz.fuzz_weight = 1.0f;
    OpenPBR_ResolvedInputs& thin = white("Thin glass");
    thin.transmission_weight = 1.0f;
    thin.specular_roughness = 0.0f;
    thin.geometry_thin_walled = true;
    OpenPBR_ResolvedInputs& subsurface = white("Subsurface");
    subsurface.subsurface_weight = 1.0f;
    subsurface.subsurface_radius_scale = glm::vec3(1.0f);
    subsurface.subsurface_radius = 0.3f;
    // Two more cases: rough refraction, and a cut-out (opacity) surface.
    OpenPBR_ResolvedInputs& rough_glass = white("Rough glass");
    rough_glass.transmission_weight = 1.0f;
    rough_glass.specular_roughness = 0.3f;
    OpenPBR_ResolvedInputs& cut_out = white("Cut-out 50%");
    cut_out.geometry_opacity = 0.5f;
    return materials;
}

std::vector<SphereStatistics> sphere_statistics(const RenderImage& image, float reference)
{
    std::vector<SphereStatistics> statistics(image.labels.size());
    for (std::size_t cell = 0; cell < image.labels.size(); ++cell)
    {
        SphereStatistics& entry = statistics[cell];
        entry.label = image.labels[cell];
        const int x0 = int(cell % std::size_t(image.columns)) * image.cell_size;
        const int y0 = int(cell / std::size_t(image.columns)) * image.cell_size;
        double sums[3] = {0.0, 0.0, 0.0};
        for (int y = y0; y < y0 + image.cell_size; ++y)
        {
            for (int x = x0; x < x0 + image.cell_size; ++x)
            {
                const std::size_t pixel = std::size_t(y) * std::size_t(image.width) + std::size_t(x);
                if (image.object_fraction[pixel] < 1.0f) continue;  // edge or background
                for (int channel = 0; channel < 3; ++channel) sums[channel] += image.mean[pixel * 3 + std::size_t(channel)];
                ++entry.pixels;
            }
        }
        for (int channel = 0; channel < 3; ++channel)
        {
            entry.mean[channel] = entry.pixels ? sums[channel] / double(entry.pixels) : 0.0;
            entry.relative_error = std::max(entry.relative_error, std::fabs(entry.mean[channel] / double(reference) - 1.0));
        }
    }
    return statistics;
}

RenderComparison compare_renders(const RenderImage& a, const RenderImage& b)
{
    if (a.width != b.width || a.height != b.height) throw std::invalid_argument("compare_renders: sizes differ");
    RenderComparison comparison;
    double squared = 0.0;
    double variance = 0.0;
    std::size_t identical = 0;
    const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
    for (std::size_t pixel = 0; pixel < pixels; ++pixel)
    {
        bool same = true;
        for (std::size_t channel = 0; channel < 3; ++channel)
        {
            const double va = a.mean[pixel * 3 + channel];
            const double vb = b.mean[pixel * 3 + channel];
            const double difference = va - vb;
            squared += difference * difference;
            variance +=
                0.5 * (double(a.variance_of_mean[pixel * 3 + channel]) + double(b.variance_of_mean[pixel * 3 + channel]));
            comparison.max_abs_difference = std::max(comparison.max_abs_difference, std::fabs(difference));
            same = same && std::fabs(difference) <= 1e-4 * std::max({std::fabs(va), std::fabs(vb), 1e-3});
        }
        identical += same ? 1 : 0;
    }
    const double count = double(pixels) * 3.0;
    comparison.rmse = std::sqrt(squared / count);
    comparison.noise = std::sqrt(variance / count);
    comparison.identical_fraction = double(identical) / double(pixels);
    comparison.nonfinite_a = a.nonfinite_samples;
    comparison.nonfinite_b = b.nonfinite_samples;
    return comparison;
}

}  // namespace openpbr::host
