// accuracy_variant_body.h - the body of one variant of host/studies/accuracy_variants.h. A variant
// file defines OPENPBR_CPP_VARIANT_NAMESPACE (e.g. vndf_bounded), the knob's macros (e.g.
// OPENPBR_VNDF_METHOD) and OPENPBR_ACCURACY_VARIANT_FACTORY (the function name, e.g.
// make_variant_vndf_bounded), then includes this file. No include guard: one inclusion per
// translation unit by design.
#include <cmath>
#include <random>

#include "host/studies/accuracy_variants.h"
#include "slang/openpbr.h"

namespace openpbr::host {

namespace OPENPBR_CPP_VARIANT_NAMESPACE {

inline ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::OpenPBR_ResolvedInputs resolve(const AccuracyMaterial& material)
{
    auto inputs = ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::openpbr_make_default_resolved_inputs();
    accuracy_apply_material(material, inputs);
    return inputs;
}

// The dialect's vec3 in this variant: glm::vec3, or glm::dvec3 in the double-precision build
// (host/studies/accuracy_double_variant.cpp).
using Vector3 = decltype(::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE::OpenPBR_DiffuseSpecular{}.diffuse);

inline Vector3 to_vec3(const float* v) { return Vector3(v[0], v[1], v[2]); }

inline void eval(const std::vector<AccuracyMaterial>& materials, const std::vector<AccuracyQuery>& queries, float* out)
{
    using namespace ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE;
    for (std::size_t i = 0; i < queries.size(); ++i)
    {
        const AccuracyQuery& query = queries[i];
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(resolve(materials[query.material]), to_vec3(query.view));
        const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, to_vec3(query.light));
        const Vector3 sum = value.diffuse + value.specular;
        out[3 * i] = float(sum.x);
        out[3 * i + 1] = float(sum.y);
        out[3 * i + 2] = float(sum.z);
    }
}

inline void sample(const std::vector<AccuracyMaterial>& materials, const std::vector<AccuracyQuery>& queries, float* out)
{
    using namespace ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE;
    for (std::size_t i = 0; i < queries.size(); ++i)
    {
        const AccuracyQuery& query = queries[i];
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(resolve(materials[query.material]), to_vec3(query.view));
        const OpenPBR_BsdfSample drawn = openpbr_sample(bsdf, to_vec3(query.u));
        const Vector3 weight = drawn.pdf > 0.0f ? drawn.weight.diffuse + drawn.weight.specular : Vector3(0.0f);
        out[3 * i] = float(weight.x);
        out[3 * i + 1] = float(weight.y);
        out[3 * i + 2] = float(weight.z);
    }
}

inline AccuracyAlbedo albedo(const AccuracyMaterial& material, float mu, std::uint32_t samples, std::uint64_t seed)
{
    using namespace ::openpbr::OPENPBR_CPP_VARIANT_NAMESPACE;
    const Vector3 view(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(resolve(material), view);
    // Roberts' R3 sequence (the generalized golden ratio, 1 / phi_3^k) with a random shift
    // from the seed: a low-discrepancy point set, so the mean converges far faster than with
    // independent numbers, while the sample variance of the weights is still the per-sample
    // variance of the estimator (what the sampling knob compares).
    std::mt19937_64 generator(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const double shift[3] = {uniform(generator), uniform(generator), uniform(generator)};
    const double step[3] = {0.8191725133961645, 0.6710436067037893, 0.5497004779019703};
    double sum[3] = {0.0, 0.0, 0.0};
    double luminance_sum = 0.0;
    double luminance_squares = 0.0;
    for (std::uint32_t s = 0; s < samples; ++s)
    {
        Vector3 u;
        for (int k = 0; k < 3; ++k)
        {
            const double value = shift[k] + step[k] * double(s);
            u[k] = float(value - std::floor(value));
        }
        const OpenPBR_BsdfSample drawn = openpbr_sample(bsdf, glm::min(u, Vector3(0.99999994f)));
        const Vector3 weight = drawn.pdf > 0.0f ? drawn.weight.diffuse + drawn.weight.specular : Vector3(0.0f);
        for (int c = 0; c < 3; ++c)
        {
            sum[c] += weight[c];
        }
        const double luminance = 0.2126 * double(weight.x) + 0.7152 * double(weight.y) + 0.0722 * double(weight.z);
        luminance_sum += luminance;
        luminance_squares += luminance * luminance;
    }
    AccuracyAlbedo result;
    for (int c = 0; c < 3; ++c)
    {
        result.mean[c] = sum[c] / samples;
    }
    const double mean_luminance = luminance_sum / samples;
    result.variance = std::max(0.0, luminance_squares / samples - mean_luminance * mean_luminance);
    return result;
}

}  // namespace OPENPBR_CPP_VARIANT_NAMESPACE

BsdfVariant OPENPBR_ACCURACY_VARIANT_FACTORY(const std::string& knob, const std::string& setting)
{
    BsdfVariant variant;
    variant.knob = knob;
    variant.setting = setting;
    variant.eval = &OPENPBR_CPP_VARIANT_NAMESPACE::eval;
    variant.sample = &OPENPBR_CPP_VARIANT_NAMESPACE::sample;
    variant.albedo = &OPENPBR_CPP_VARIANT_NAMESPACE::albedo;
    return variant;
}

}  // namespace openpbr::host
