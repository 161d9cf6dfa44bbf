// A C++ consumer of the installed openpbr package (README "Integrating"): a few lines of BSDF
// use, then checks that fail loudly (exit 1) when the library misbehaves:
//   - every result over the shared queries (examples/consumer_common) is finite, eval >= 0,
//     pdf >= 0;
//   - a white furnace: a white rough metal scatters all light (albedo 1 within the tolerance
//     below) and a white plastic no more than all of it;
//   - lobe-type flags: a mirror's samples are specular reflections, a rough metal's glossy;
//   - the coat frame follows geometry_basis when only that is set.
#include <cmath>
#include <cstdio>

#include "openpbr_consumer.h"

using namespace openpbr_consumer;

namespace {

// Mean sample weight over a stratified n x n grid of random numbers: the directional albedo
// seen from `view` (BSDF x |cos| / pdf averaged, delta lobes included).
float albedo(const OpenPBR_ResolvedInputs& material, const vec3& view, int n)
{
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(material, view);
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; j < n; ++j)
        {
            const vec3 u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n),
                         (float(i * n + j) + 0.5f) / float(n * n));
            const OpenPBR_BsdfSample s = openpbr_sample(bsdf, u);
            if (s.pdf > 0.0f)
            {
                sum += double(s.weight.diffuse.y + s.weight.specular.y);
            }
        }
    }
    return float(sum / double(n * n));
}

int failures = 0;
void check(bool condition, const char* what)
{
    std::printf("  %s: %s\n", condition ? "ok  " : "FAIL", what);
    failures += condition ? 0 : 1;
}

}  // namespace

int main()
{
    // The README's snippet.
    OpenPBR_ResolvedInputs material = openpbr_make_default_resolved_inputs();
    material.base_color = vec3(0.9f, 0.5f, 0.2f);
    material.geometry_basis = openpbr_make_basis(vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f), 1.0f);
    const vec3 view = normalize(vec3(0.3f, 0.1f, 1.0f));
    const vec3 light = normalize(vec3(-0.4f, 0.2f, 1.0f));
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(material, view);
    const OpenPBR_DiffuseSpecular f = openpbr_eval(bsdf, light);
    std::printf("cpp_consumer: eval diffuse (%g %g %g) specular (%g %g %g), pdf %g\n", f.diffuse.x, f.diffuse.y, f.diffuse.z,
                f.specular.x, f.specular.y, f.specular.z, openpbr_pdf(bsdf, light));

    const std::vector<OpenPBR_ResolvedInputs> materials = make_materials();
    const std::vector<float> queries = make_queries(1024, materials.size());
    const std::vector<float> results = shade_all_on_cpu(materials, queries);
    bool valid = true;
    for (std::size_t q = 0; q < results.size() / result_floats; ++q)
    {
        const float* r = results.data() + q * result_floats;
        for (std::size_t slot = 0; slot < result_floats; ++slot)
        {
            valid = valid && std::isfinite(r[slot]);
        }
        for (int slot : {0, 1, 2, 3, 4, 5, 6, 11})
        {
            valid = valid && r[slot] >= 0.0f;
        }
    }
    check(valid, "1024 queries: finite, eval >= 0, pdf >= 0");

    // White furnace at a 60-degree view. The project's furnace check (host/checks/furnace.h)
    // holds a white metal to |1 - albedo| <= 0.005; this 64 x 64 stratified estimate measured
    // 1.0007 for the metal and 0.9905 for the plastic (its base gets what the specular layer
    // leaves), so 0.01 leaves room for the estimator and still fails on a lost or doubled lobe.
    const vec3 furnace_view = vec3(std::sqrt(0.75f), 0.0f, 0.5f);
    OpenPBR_ResolvedInputs white_metal = openpbr_make_default_resolved_inputs();
    white_metal.base_metalness = 1.0f;
    white_metal.base_color = vec3(1.0f);
    white_metal.specular_color = vec3(1.0f);
    white_metal.specular_roughness = 0.5f;
    const float metal_albedo = albedo(white_metal, furnace_view, 64);
    std::printf("  white metal albedo %.4f\n", metal_albedo);
    check(std::fabs(metal_albedo - 1.0f) <= 0.01f, "white rough metal: albedo 1 +- 0.01");
    OpenPBR_ResolvedInputs white_plastic = openpbr_make_default_resolved_inputs();
    white_plastic.base_color = vec3(1.0f);
    white_plastic.specular_roughness = 0.3f;
    const float plastic_albedo = albedo(white_plastic, furnace_view, 64);
    std::printf("  white plastic albedo %.4f\n", plastic_albedo);
    check(plastic_albedo <= 1.01f && plastic_albedo > 0.5f, "white plastic: 0.5 < albedo <= 1 + 0.01");

    // Lobe-type flags (the lobe id sits above the flags, so the helpers, not ==).
    const OpenPBR_BsdfSample mirror_sample =
        openpbr_sample(openpbr_prepare(materials[5], furnace_view), vec3(0.3f, 0.6f, 0.2f));
    check(openpbr_lobe_type_is_specular(mirror_sample.lobe_type) &&
              openpbr_lobe_type_is_reflection(mirror_sample.lobe_type) &&
              openpbr_lobe_type_id(mirror_sample.lobe_type) == OPENPBR_LOBE_ID_METAL,
          "mirror metal: specular reflection from the metal lobe");
    const OpenPBR_BsdfSample gold_sample =
        openpbr_sample(openpbr_prepare(materials[1], furnace_view), vec3(0.3f, 0.6f, 0.2f));
    check(openpbr_lobe_type_is_glossy(gold_sample.lobe_type) && !openpbr_lobe_type_is_specular(gold_sample.lobe_type),
          "rough gold: glossy, not specular");

    // The coat frame follows geometry_basis (set alone in make_materials) exactly as if set too.
    OpenPBR_ResolvedInputs coated_both = materials[2];
    coated_both.geometry_coat_basis = tilted_frame();
    const OpenPBR_DiffuseSpecular coated_alone = openpbr_eval(openpbr_prepare(materials[2], view), light);
    const OpenPBR_DiffuseSpecular coated_set = openpbr_eval(openpbr_prepare(coated_both, view), light);
    check(coated_alone.specular == coated_set.specular && coated_alone.diffuse == coated_set.diffuse,
          "coat frame follows geometry_basis");

    std::printf("cpp_consumer: %s\n", failures ? "FAILED" : "all checks passed");
    return failures ? 1 : 0;
}
