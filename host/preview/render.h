// render.h - a small preview path tracer over the OpenPBR BSDF: a labelled gallery of
// material spheres and a white furnace, rendered by one kernel body
// (targets/kernels/openpbr_render_kernel.h) on the CPU (TBB over pixels) or as a Vulkan
// compute shader (targets/kernels/render.slang, lavapipe on machines without a GPU).
//
// Units: radiance in "render units"; emission (nits) is converted with
// kNitsToRenderUnits (1 render unit = 100 nits, SDR reference white), so the 10000-nit light
// bulb material is 100 units and a 200-nit display 2 units. The sky is about 0.2 to 0.9 units,
// the area light 40 units. Radiance is in the library's working space (the loader converts
// the materials' colours into it; the scene's light and sky are given in linear Rec.709 and
// converted too). The view transform (docs/colour.md): exposure, working space -> linear
// Rec.709 (the display's primaries), the ACES filmic fit of Narkowicz (2015), then the sRGB
// transfer function.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "host/scene/material_library.h"

namespace openpbr::host {

constexpr float kNitsToRenderUnits = 0.01f;

enum class RenderBackend
{
    cpu,
    vulkan
};

const char* to_string(RenderBackend backend);

struct RenderSettings
{
    int cell_size = 128;  // pixels per (square) cell, one material per cell
    int columns = 0;      // 0: chosen from the material count (about 8:7 for 55)
    int samples_per_pixel = 32;
    std::uint32_t seed = 1;
    int max_depth = 8;             // surface scattering events
    int max_volume_events = 256;   // scattering events in a medium
    int roulette_depth = 3;        // Russian roulette from this many events on
    bool furnace = false;          // uniform environment only: no ground, no light, no sky
    float environment = 1.0f;      // furnace environment radiance (render units)
    bool area_light = true;        // the area light (not in the furnace); false, e.g. for low-noise
                                   // comparisons: sky and ground only, no fireflies of the small light
    bool progress = true;          // progress bar with time left on stderr
    std::string progress_label;    // e.g. "cpu"; empty: the backend's name
    int chunk_samples = 0;         // samples per pass (CPU) or dispatch (Vulkan); 0: automatic
    std::string kernel_directory;  // where render.slang.spv is (Vulkan)
};

struct RenderImage
{
    int width = 0;
    int height = 0;
    int cell_size = 0;
    int columns = 0;
    int rows = 0;
    int samples_per_pixel = 0;
    std::vector<std::string> labels;      // one per cell with objects
    std::vector<float> mean;              // linear RGB per pixel, row-major from the top
    std::vector<float> variance_of_mean;  // per pixel and channel: sample variance / spp
    std::vector<float> object_fraction;   // per pixel: share of camera rays that hit an object
    std::uint64_t nonfinite_samples = 0;  // non-finite samples, replaced by 0
    double seconds = 0.0;                 // wall time of the whole render (setup included)
    double first_pass_seconds = 0.0;      // the first pass/dispatch (Vulkan: includes the JIT)
    double ns_per_pixel_sample = 0.0;     // wall time / (pixels x spp), setup excluded
    std::string device;                   // "N TBB threads" or the Vulkan device's name
};

// One sphere of a cell, in the cell's coordinates: the ground is the plane y = -1 and the
// camera frames the unit sphere at the origin (a plain gallery cell is that sphere alone).
struct RenderObject
{
    Material material;
    float center[3] = {0.0f, 0.0f, 0.0f};  // e.g. {0.2, 0.1, 0.3} for a bubble off the middle
    float radius = 1.0f;                   // > 0, e.g. 0.9 for the water in a glass shell
};

// A cell of the image: its label and its objects, at most kRenderMaxObjects, listed from the
// outside in. Nested media (targets/kernels/openpbr_render_kernel.h): a path inside several
// objects is in the medium of the last-listed one (its priority is its index), and the surface
// of an object is the interface between its medium (IOR = its specular_ior, its volume from
// transmission_color/depth or subsurface) and the medium around it, so its material is
// prepared with that medium's IOR as exterior_ior. Thin-walled objects have no medium.
// Example, water in a glass shell: {glass, radius 1}, {water, radius 0.9}.
struct RenderCell
{
    std::string label;
    std::vector<RenderObject> objects;
};

constexpr int kRenderMaxObjects = 4;  // = OPENPBR_RENDER_MAX_OBJECTS (checked in render.cpp)

// Renders the cells (in order, row-major), on the chosen backend. Throws std::invalid_argument
// for a cell without objects, with more than kRenderMaxObjects, or with an object that is not
// finite, has a radius <= 0 or reaches below the ground; std::runtime_error when the Vulkan
// backend has no device (see vulkan_render_available) or a step fails.
RenderImage render_cells(const std::vector<RenderCell>& cells, const RenderSettings& settings, RenderBackend backend);

// One cell per material: the unit sphere at the origin, labelled with the material's name.
std::vector<RenderCell> material_cells(const std::vector<Material>& materials);

// Renders material_cells(materials).
RenderImage render_materials(const std::vector<Material>& materials, const RenderSettings& settings, RenderBackend backend);

// Water for the nested-media scenes: a smooth dielectric of IOR 1.33 with a faint blue-green
// absorption (transmission_color 0.86/0.96/0.97 over transmission_depth 2, i.e. per two unit
// radii); white and non-absorbing when `white` (for the furnace).
Material water_material(bool white);

// Air as a material: a smooth dielectric of IOR 1 (a bubble: invisible in air, an interface
// of relative IOR 1/1.33 in water).
Material air_material();

// The nested-media scenes of the gallery, built from spheres (the renderer's only primitive):
// "Glass of water" (a round bowl of the bundled Glass material, radius 1, filled with a water
// sphere of radius 0.9, a wall 0.1 thick: the water/glass interface has relative IOR
// 1.33/1.52 seen from the water) and "Air bubble in water" (a water sphere of
// radius 1 with an air sphere of radius 0.45 off its middle). `glass` is the glass material
// (the bundled one in the gallery). When `white` (for the furnace), every color of the glass
// and the water is white, nothing absorbs and the glass is not dispersive.
std::vector<RenderCell> nested_media_cells(const Material& glass, bool white);

// Whether a Vulkan device can be created; the reason in *reason when not.
bool vulkan_render_available(std::string* reason);

// The neutral ground: default OpenPBR inputs with a mid-grey base and a rough specular; the
// kernel multiplies its base color by a checker (1 or 0.55).
Material render_ground_material();

// White, non-emissive, non-absorbing configurations for the furnace test: white diffuse under
// white specular, white metal, white glass (smooth), white coat over white, white fuzz over
// white, thin-walled white glass, white subsurface; then rough white glass and a white
// surface with geometry_opacity 0.5.
std::vector<Material> furnace_materials();

struct SphereStatistics
{
    std::string label;
    double mean[3] = {0.0, 0.0, 0.0};  // over the pixels fully covered by the sphere
    double relative_error = 0.0;       // max over channels of |mean / reference - 1|
    std::size_t pixels = 0;
};

// Mean radiance over each sphere's fully covered pixels, against a reference radiance.
std::vector<SphereStatistics> sphere_statistics(const RenderImage& image, float reference);

struct RenderComparison
{
    double rmse = 0.0;   // RMS over pixels and channels of a - b (linear)
    double noise = 0.0;  // RMS standard error of one render (mean of both images' estimates)
    double max_abs_difference = 0.0;
    double identical_fraction = 0.0;  // pixels whose three channels agree to 1e-4 relative
    std::uint64_t nonfinite_a = 0;
    std::uint64_t nonfinite_b = 0;
};

RenderComparison compare_renders(const RenderImage& a, const RenderImage& b);

// PNG of the tone-mapped image (exposure, to Rec.709, ACES fit, sRGB), with the cell labels when asked.
void write_render_png(const std::string& path, const RenderImage& image, float exposure, bool labels);

// PNG of |a - b| x scale, per channel, gamma-encoded (sRGB transfer function, no tone curve).
void write_difference_png(const std::string& path, const RenderImage& a, const RenderImage& b, float scale);

}  // namespace openpbr::host
