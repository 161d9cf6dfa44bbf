// The texture units' stand-in of texture_sampler.h.
#include "tests/api_compat/texture_luts/texture_sampler.h"

#include "slang/openpbr_lut.h"
#include "slang/lobes/openpbr_fuzz_lobe.h"

#include <cmath>

namespace texture_luts_host {

int subtexel_bits = 0;
long long fetch_count = 0;

namespace {

const float lut_values[] = {
#include "slang/generated/openpbr_lut_values.inc"
    ,
#include "slang/generated/openpbr_film_lut_values.inc"
};
const float fuzz_values[] = {
#include "slang/generated/openpbr_fuzz_ltc_values.inc"
};

struct Texture
{
    const float* texels;
    int width;
    int height;
    int depth;
};

// Filled as slang/openpbr_lut_textures.h's table says.
Texture texture_of(int lut_id)
{
    const int n3 = OPENPBR_LUT_3D_SIZE;
    const int e3 = OPENPBR_LUT_3D_ETA_SIZE;
    switch (lut_id)
    {
    case OPENPBR_LUT_TEXTURE_GGX_ALBEDO:
        return {lut_values + OPENPBR_LUT_GGX_ALBEDO_OFFSET, OPENPBR_LUT_2D_SIZE, OPENPBR_LUT_2D_SIZE, 1};
    case OPENPBR_LUT_TEXTURE_DIELECTRIC_REFLECTION:
        return {lut_values + OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET, n3, n3, e3};
    case OPENPBR_LUT_TEXTURE_DIELECTRIC_TRANSMISSION:
        return {lut_values + OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET, n3, n3, e3};
    case OPENPBR_LUT_TEXTURE_DIELECTRIC_INTERFACE: return {lut_values + OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET, n3, n3, e3};
    case OPENPBR_LUT_TEXTURE_GGX_ANISOTROPY_RATIO:
        return {lut_values + OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET, OPENPBR_LUT_4D_SIZE, OPENPBR_LUT_4D_SIZE,
                OPENPBR_LUT_4D_ANISOTROPY_SIZE * OPENPBR_LUT_4D_ANISOTROPY_SIZE};
    case OPENPBR_LUT_TEXTURE_FILM_LOBE:
        return {lut_values + OPENPBR_LUT_FILM_OFFSET, OPENPBR_LUT_FILM_QUANTILE_SIZE, OPENPBR_LUT_FILM_SIZE,
                OPENPBR_LUT_FILM_CHANNEL_COUNT * OPENPBR_LUT_FILM_SIZE};
    case OPENPBR_LUT_TEXTURE_FUZZ_LTC_A:
        return {fuzz_values + OPENPBR_FUZZ_LTC_A_OFFSET, OPENPBR_FUZZ_LTC_SIZE, OPENPBR_FUZZ_LTC_SIZE, 1};
    case OPENPBR_LUT_TEXTURE_FUZZ_LTC_B:
        return {fuzz_values + OPENPBR_FUZZ_LTC_B_OFFSET, OPENPBR_FUZZ_LTC_SIZE, OPENPBR_FUZZ_LTC_SIZE, 1};
    default: return {fuzz_values + OPENPBR_FUZZ_LTC_R_OFFSET, OPENPBR_FUZZ_LTC_SIZE, OPENPBR_FUZZ_LTC_SIZE, 1};
    }
}

// One axis of linear filtering: the two texel indices (clamped to the edge) and the weight.
struct Axis
{
    int first;
    int second;
    float weight;
};

Axis filter_axis(float coordinate, int size)
{
    const float texel = coordinate * float(size) - 0.5f;
    const float lower = std::floor(texel);
    float weight = texel - lower;
    if (subtexel_bits > 0)
    {
        const float steps = float(1 << subtexel_bits);
        weight = std::round(weight * steps) / steps;
    }
    const int first = int(lower);
    const auto clamp_index = [size](int index) { return index < 0 ? 0 : (index >= size ? size - 1 : index); };
    return {clamp_index(first), clamp_index(first + 1), weight};
}

}  // namespace

float sample_2d(int lut_id, glm::vec2 uv)
{
    ++fetch_count;
    const Texture texture = texture_of(lut_id);
    const Axis x = filter_axis(uv.x, texture.width);
    const Axis y = filter_axis(uv.y, texture.height);
    const auto at = [&](int i, int j) { return texture.texels[j * texture.width + i]; };
    const float low = at(x.first, y.first) + (at(x.second, y.first) - at(x.first, y.first)) * x.weight;
    const float high = at(x.first, y.second) + (at(x.second, y.second) - at(x.first, y.second)) * x.weight;
    return low + (high - low) * y.weight;
}

float sample_3d(int lut_id, glm::vec3 uvw)
{
    ++fetch_count;
    const Texture texture = texture_of(lut_id);
    const Axis x = filter_axis(uvw.x, texture.width);
    const Axis y = filter_axis(uvw.y, texture.height);
    const Axis z = filter_axis(uvw.z, texture.depth);
    const auto at = [&](int i, int j, int k) { return texture.texels[(k * texture.height + j) * texture.width + i]; };
    const auto slice = [&](int k) {
        const float low = at(x.first, y.first, k) + (at(x.second, y.first, k) - at(x.first, y.first, k)) * x.weight;
        const float high = at(x.first, y.second, k) + (at(x.second, y.second, k) - at(x.first, y.second, k)) * x.weight;
        return low + (high - low) * y.weight;
    };
    const float front = slice(z.first);
    const float back = slice(z.second);
    return front + (back - front) * z.weight;
}

}  // namespace texture_luts_host
