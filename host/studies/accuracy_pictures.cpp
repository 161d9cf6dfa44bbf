// accuracy_pictures.cpp - the accuracy study's picture strips (host/studies/accuracy_internal.h):
// per knob family one material where the knob matters, one image per setting computed without
// noise, so a setting's difference from the reference is the knob's and nothing else:
//   - BSDF strips: a unit sphere seen along -z (orthographic) under one distant light, pixel =
//     eval(view, light) x cos(light) x pi (a white Lambertian surface facing the light reads 1);
//   - the film strip: the soap bubble's film reflectance at the pixel's view cosine (what the
//     mirror-smooth bubble reflects of a uniform white sky);
//   - the sampling strip (a variance knob): the albedo under a white sky estimated with 4 samples
//     per pixel, the same point set per pixel for every setting, against 1024 samples.
// Output: float32 RGB images (row-major, top row first; -1 outside the sphere) and manifest.json,
// which tools/accuracy_figures.py turns into docs/images/accuracy-*.png.
#include <cmath>
#include <functional>

#include "host/scene/material_packing.h"
#include "host/studies/accuracy_internal.h"
#include "host/support/files.h"

namespace openpbr::host::accuracy {
namespace {

struct Vector
{
    float x, y, z;
};

float dot(const Vector& a, const Vector& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vector normalized(const Vector& v)
{
    const float length = std::sqrt(dot(v, v));
    return {v.x / length, v.y / length, v.z / length};
}

// The sphere's pixels: per pixel inside the disc the normal and the shading frame (tangent
// horizontal, so an anisotropic material is brushed left to right).
struct SpherePixel
{
    std::size_t index;
    Vector normal, tangent, bitangent;
};

std::vector<SpherePixel> sphere_pixels(const int size)
{
    std::vector<SpherePixel> pixels;
    for (int y = 0; y < size; ++y)
    {
        for (int x = 0; x < size; ++x)
        {
            const float px = (float(x) + 0.5f) / float(size) * 2.0f - 1.0f;
            const float py = 1.0f - (float(y) + 0.5f) / float(size) * 2.0f;
            const float r2 = px * px + py * py;
            if (r2 >= 0.995f)
            {
                continue;
            }
            const Vector normal{px, py, std::sqrt(1.0f - r2)};
            const Vector tangent = normalized({normal.z, 0.0f, -normal.x});
            const Vector bitangent{normal.y * tangent.z - normal.z * tangent.y, normal.z * tangent.x - normal.x * tangent.z,
                                   normal.x * tangent.y - normal.y * tangent.x};
            pixels.push_back({std::size_t(y) * std::size_t(size) + std::size_t(x), normal, tangent, bitangent});
        }
    }
    return pixels;
}

void to_local(const SpherePixel& pixel, const Vector& direction, float* out)
{
    out[0] = dot(direction, pixel.tangent);
    out[1] = dot(direction, pixel.bitangent);
    out[2] = dot(direction, pixel.normal);
}

// One image per setting from `pixel_value(variant, pixel, rgb out)`.
using PixelValue = std::function<void(const BsdfVariant&, const std::vector<SpherePixel>&, std::vector<float>&)>;

struct Strip
{
    std::string name;                                           // file prefix, e.g. "compensation"
    std::string family;                                         // e.g. "compensation"
    std::string material;                                       // what is shown, e.g. "rough white metal (roughness 0.8)"
    std::string quantity;                                       // what a pixel is
    std::string reference;                                      // the variant the differences are taken against
    std::vector<std::pair<std::string, std::string>> settings;  // variant, label; reference first
};

nlohmann::json write_strip(const StudyContext& context, const Strip& strip, const int size, const PixelValue& value)
{
    const std::filesystem::path directory = context.options.pictures_directory;
    const std::vector<SpherePixel> pixels = sphere_pixels(size);
    nlohmann::json tiles = nlohmann::json::array();
    for (const auto& [name, label] : strip.settings)
    {
        std::vector<float> image(std::size_t(size) * std::size_t(size) * 3, -1.0f);
        value(variant_named(context.variants, name), pixels, image);
        const std::string file = strip.name + "_" + name + ".f32";
        write_float32_file(directory / file, image);
        tiles.push_back({{"variant", name}, {"setting", label}, {"file", file}, {"reference", name == strip.reference}});
    }
    return {{"name", strip.name},
            {"family", strip.family},
            {"material", strip.material},
            {"quantity", strip.quantity},
            {"reference", strip.reference},
            {"width", size},
            {"height", size},
            {"tiles", tiles}};
}

// eval x cos x pi under the study's light, the material packed once.
PixelValue lit_sphere(const Material& material)
{
    return [packed = pack_materials({material})](const BsdfVariant& variant, const std::vector<SpherePixel>& pixels,
                                                 std::vector<float>& image) {
        const Vector light = normalized({-0.45f, 0.55f, 0.7f});
        std::vector<AccuracyQuery> queries(pixels.size());
        for (std::size_t i = 0; i < pixels.size(); ++i)
        {
            to_local(pixels[i], {0.0f, 0.0f, 1.0f}, queries[i].view);
            to_local(pixels[i], light, queries[i].light);
        }
        std::vector<float> values(3 * queries.size());
        variant.eval(packed.data(), queries, values.data());
        for (std::size_t i = 0; i < pixels.size(); ++i)
        {
            const float cosine = std::max(queries[i].light[2], 0.0f) * 3.14159265f;
            for (std::size_t c = 0; c < 3; ++c)
            {
                image[3 * pixels[i].index + c] = values[3 * i + c] * cosine;
            }
        }
    };
}

Material material_from_file(const StudyContext& context, const std::string& file)
{
    return load_materialx_file((context.options.repository_root / "materials" / file).string()).front();
}

}  // namespace

void write_picture_strips(const StudyContext& context)
{
    const AccuracyOptions& options = context.options;
    std::filesystem::create_directories(options.pictures_directory);
    const int size = options.quick ? 24 : 112;
    nlohmann::json strips = nlohmann::json::array();
    Material rough_metal = metal_material(0.95f, 0.8f);
    strips.push_back(write_strip(context,
                                 {"compensation",
                                  "compensation",
                                  "rough white metal (base_color 0.95, roughness 0.8)",
                                  "eval x cos under one light",
                                  "compensation_exact",
                                  {{"compensation_exact", "exact E (reference)"},
                                   {"shipped", "table 128 (shipped)"},
                                   {"table_64", "table 64"},
                                   {"table_16", "table 16"},
                                   {"compensation_analytic", "analytic fit"},
                                   {"compensation_none", "none"}}},
                                 size, lit_sphere(rough_metal)));
    strips.push_back(write_strip(
        context,
        {"table_storage",
         "table storage",
         "materials/open_pbr_aluminum_brushed.mtlx",
         "eval x cos under one light",
         "shipped",
         {{"shipped", "float32 array (shipped)"}, {"table_buffer", "float32 buffer"}, {"table_half", "16-bit values"}}},
        size, lit_sphere(material_from_file(context, "open_pbr_aluminum_brushed.mtlx"))));
    const Material velvet = material_from_file(context, "open_pbr_velvet.mtlx");
    strips.push_back(write_strip(context,
                                 {"fast_math",
                                  "fast math",
                                  "materials/open_pbr_velvet.mtlx",
                                  "eval x cos under one light",
                                  "shipped",
                                  {{"shipped", "precise (shipped)"},
                                   {"fast_rcp_sqrt", "FAST_RCP_SQRT"},
                                   {"fast_sqrt", "FAST_SQRT + RCP_SQRT"},
                                   {"fast_normalize", "FAST_NORMALIZE + RCP_SQRT"},
                                   {"fast_all", "all hooks"}}},
                                 size, lit_sphere(velvet)));
    strips.push_back(write_strip(context,
                                 {"precision",
                                  "precision",
                                  "materials/open_pbr_velvet.mtlx",
                                  "eval x cos under one light",
                                  "double_precision",
                                  {{"double_precision", "double (reference)"}, {"shipped", "float (shipped)"}}},
                                 size, lit_sphere(velvet)));
    Material stack = film_stack_materials()[7];  // film 0.9 um, roughness 0.4
    strips.push_back(write_strip(context,
                                 {"film_estimate",
                                  "film estimate",
                                  "white base under a 0.9 um film of IOR 1.4 under a coat of IOR 1.6, roughness 0.4",
                                  "eval x cos under one light",
                                  "shipped",
                                  {{"shipped", "shipped cuts"},
                                   {"film_estimate_quartile_cuts", "coarse cuts"},
                                   {"film_estimate_at_view", "film at the view"}}},
                                 size, lit_sphere(stack)));
    const auto bubble = [](const BsdfVariant& variant, const std::vector<SpherePixel>& pixels, std::vector<float>& image) {
        // materials/open_pbr_soapbubble.mtlx: a 0.5 um film of IOR 1.4 in air on both sides.
        const AccuracyFilm film{1.0f, 1.4f, 0.5f, 1.0f, 0.0f, 1.0f};
        for (const SpherePixel& pixel : pixels)
        {
            variant.film_reflectance(film, pixel.normal.z, &image[3 * pixel.index]);
        }
    };
    strips.push_back(write_strip(context,
                                 {"thin_film",
                                  "thin film",
                                  "materials/open_pbr_soapbubble.mtlx",
                                  "film reflectance at the view (the bubble under a white sky)",
                                  "shipped",
                                  {{"shipped", "full film (shipped)"}, {"thin_film_fast", "fast approximation"}}},
                                 size, bubble));
    const std::vector<float> sampled_metal = pack_materials({metal_material(0.95f, 0.6f)});
    const auto sampled = [&](const std::uint32_t samples) {
        return [&, samples](const BsdfVariant& variant, const std::vector<SpherePixel>& pixels, std::vector<float>& image) {
            for (const SpherePixel& pixel : pixels)
            {
                const AccuracyAlbedo albedo = variant.albedo(sampled_metal.data(), pixel.normal.z, samples, pixel.index);
                for (std::size_t c = 0; c < 3; ++c)
                {
                    image[3 * pixel.index + c] = float(albedo.mean[c]);
                }
            }
        };
    };
    nlohmann::json sampling = write_strip(
        context,
        {"vndf_sampling",
         "vndf sampling",
         "metal (base_color 0.95, roughness 0.6)",
         "directional albedo under a white sky, 4 samples per pixel",
         "shipped",
         {{"shipped", "spherical caps (shipped)"}, {"vndf_hemisphere", "Heitz 2018"}, {"vndf_bounded", "bounded"}}},
        size, sampled(4));
    // The converged image the noise is measured against: the shipped sampler at 1024 samples.
    std::vector<float> converged(std::size_t(size) * std::size_t(size) * 3, -1.0f);
    sampled(1024)(variant_named(context.variants, "shipped"), sphere_pixels(size), converged);
    write_float32_file(options.pictures_directory / "vndf_sampling_converged.f32", converged);
    sampling["converged"] = {{"file", "vndf_sampling_converged.f32"}, {"setting", "spherical caps, 1024 samples"}};
    strips.push_back(sampling);
    write_file_atomically(options.pictures_directory / "manifest.json", nlohmann::json{{"strips", strips}}.dump(1) + "\n");
}

}  // namespace openpbr::host::accuracy
