// OPENPBR_USE_CUSTOM_VEC_TYPES=1 (C++): a renderer with its own vector library, no GLM anywhere.
// The library below (rmath) stands for the renderer's: vec2/vec3/vec4 and the GLSL math
// functions the dialect calls, made visible in namespace openpbr before the include. The
// program must compile without GLM (GLM_VERSION stays undefined: with the hook ignored the C++
// backend would stop with its "include <glm/glm.hpp>" error, or include GLM itself) and shade:
// each sample's weight equals eval / pdf at its direction, and the albedo estimate lies in
// (0, 1]. (The standard GLM build is not linked in: its inline functions would meet these.)
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rmath {

struct vec2
{
    float x = 0.0f, y = 0.0f;
    vec2() = default;
    explicit vec2(float s) : x(s), y(s) {}
    vec2(float a, float b) : x(a), y(b) {}
    float& operator[](int i) { return i == 0 ? x : y; }
    float operator[](int i) const { return i == 0 ? x : y; }
};
struct vec3
{
    float x = 0.0f, y = 0.0f, z = 0.0f;
    vec3() = default;
    explicit vec3(float s) : x(s), y(s), z(s) {}
    vec3(float a, float b, float c) : x(a), y(b), z(c) {}
    vec3(const vec2& v, float c) : x(v.x), y(v.y), z(c) {}
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
struct vec4
{
    float x = 0.0f, y = 0.0f, z = 0.0f, w = 0.0f;
    vec4() = default;
    explicit vec4(float s) : x(s), y(s), z(s), w(s) {}
    vec4(float a, float b, float c, float d) : x(a), y(b), z(c), w(d) {}
    vec4(const vec3& v, float d) : x(v.x), y(v.y), z(v.z), w(d) {}
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
};

template <class V> struct size_of;
template <> struct size_of<vec2>
{
    static constexpr int value = 2;
};
template <> struct size_of<vec3>
{
    static constexpr int value = 3;
};
template <> struct size_of<vec4>
{
    static constexpr int value = 4;
};
template <class V> using vector_only = decltype(size_of<V>::value);

// Component-wise application of a float function to one, two or three arguments (each a vector
// or a float broadcast to all components).
inline float component(float s, int) { return s; }
template <class V, class = vector_only<V>> float component(const V& v, int i) { return v[i]; }
template <class V, class F, class... A> V componentwise(F f, const A&... a)
{
    V result;
    for (int i = 0; i < size_of<V>::value; ++i)
    {
        result[i] = f(component(a, i)...);
    }
    return result;
}

#define RMATH_BINARY(op)                                                             \
    template <class V, class = vector_only<V>> V operator op(const V& a, const V& b) \
    {                                                                                \
        return componentwise<V>([](float p, float q) { return p op q; }, a, b);      \
    }                                                                                \
    template <class V, class = vector_only<V>> V operator op(const V& a, float b)    \
    {                                                                                \
        return componentwise<V>([](float p, float q) { return p op q; }, a, b);      \
    }                                                                                \
    template <class V, class = vector_only<V>> V operator op(float a, const V& b)    \
    {                                                                                \
        return componentwise<V>([](float p, float q) { return p op q; }, a, b);      \
    }                                                                                \
    template <class V, class B, class = vector_only<V>> V& operator op##=(V& a, const B& b) { return a = a op b; }
RMATH_BINARY(+)
RMATH_BINARY(-)
RMATH_BINARY(*)
RMATH_BINARY(/)
template <class V, class = vector_only<V>> V operator-(const V& a)
{
    return componentwise<V>([](float p) { return -p; }, a);
}
template <class V, class = vector_only<V>> bool operator==(const V& a, const V& b)
{
    for (int i = 0; i < size_of<V>::value; ++i)
    {
        if (a[i] != b[i]) return false;
    }
    return true;
}

// The GLSL functions on floats (std's, plus GLSL's own names) ...
using std::abs;
using std::acos;
using std::asin;
using std::atan;
using std::cos;
using std::exp;
using std::exp2;
using std::floor;
using std::log;
using std::log2;
using std::pow;
using std::sin;
using std::sqrt;
using std::tan;
inline float max(float a, float b) { return a > b ? a : b; }
inline float min(float a, float b) { return a < b ? a : b; }
inline float clamp(float x, float low, float high) { return min(max(x, low), high); }
inline float mix(float a, float b, float t) { return a + (b - a) * t; }
inline float fract(float x) { return x - std::floor(x); }
inline float inversesqrt(float x) { return 1.0f / std::sqrt(x); }
inline float sign(float x) { return float(x > 0.0f) - float(x < 0.0f); }
inline float saturate(float x) { return clamp(x, 0.0f, 1.0f); }

// ... and component-wise on vectors.
#define RMATH_UNARY(name)                                                   \
    template <class V, class = vector_only<V>> V name(const V& v)           \
    {                                                                       \
        return componentwise<V>([](float p) { return rmath::name(p); }, v); \
    }
RMATH_UNARY(abs)
RMATH_UNARY(sqrt)
RMATH_UNARY(exp)
RMATH_UNARY(log)
RMATH_UNARY(sin)
RMATH_UNARY(cos)
RMATH_UNARY(floor)
RMATH_UNARY(fract)
RMATH_UNARY(inversesqrt)
RMATH_UNARY(sign)
RMATH_UNARY(saturate)
template <class V, class = vector_only<V>> V step(const V& edge, const V& x)
{
    return componentwise<V>([](float e, float p) { return p < e ? 0.0f : 1.0f; }, edge, x);
}
template <class V, class B, class = vector_only<V>> V max(const V& a, const B& b)
{
    return componentwise<V>([](float p, float q) { return p > q ? p : q; }, a, b);
}
template <class V, class B, class = vector_only<V>> V min(const V& a, const B& b)
{
    return componentwise<V>([](float p, float q) { return p < q ? p : q; }, a, b);
}
template <class V, class B, class C, class = vector_only<V>> V clamp(const V& x, const B& low, const C& high)
{
    return min(max(x, low), high);
}
template <class V, class T, class = vector_only<V>> V mix(const V& a, const V& b, const T& t)
{
    return componentwise<V>([](float p, float q, float s) { return p + (q - p) * s; }, a, b, t);
}
template <class V, class B, class = vector_only<V>> V pow(const V& a, const B& b)
{
    return componentwise<V>([](float p, float q) { return std::pow(p, q); }, a, b);
}
template <class V, class = vector_only<V>> float dot(const V& a, const V& b)
{
    float sum = 0.0f;
    for (int i = 0; i < size_of<V>::value; ++i)
    {
        sum += a[i] * b[i];
    }
    return sum;
}
inline vec3 cross(const vec3& a, const vec3& b)
{
    return vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
// GLSL's reflect and refract (incident I towards the surface, normal N, eta = n1 / n2).
inline vec3 reflect(const vec3& incident, const vec3& normal) { return incident - 2.0f * dot(normal, incident) * normal; }
inline vec3 refract(const vec3& incident, const vec3& normal, float eta)
{
    const float cosine = dot(normal, incident);
    const float k = 1.0f - eta * eta * (1.0f - cosine * cosine);
    return k < 0.0f ? vec3(0.0f) : eta * incident - (eta * cosine + std::sqrt(k)) * normal;
}
template <class V, class = vector_only<V>> float length(const V& v) { return std::sqrt(dot(v, v)); }
template <class V, class = vector_only<V>> V normalize(const V& v) { return v / length(v); }

}  // namespace rmath

// The renderer makes its library visible where the BSDF's code lives.
namespace openpbr {
using namespace rmath;
}

#define OPENPBR_USE_CUSTOM_VEC_TYPES 1
#include "slang/openpbr.h"

#if defined(GLM_VERSION)
#error "OPENPBR_USE_CUSTOM_VEC_TYPES=1, but the BSDF pulled in GLM"
#endif

int main()
{
    using namespace openpbr;
    int failures = 0;
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    inputs.base_color = rmath::vec3(0.8f, 0.5f, 0.3f);
    inputs.coat_weight = 0.5f;
    inputs.fuzz_weight = 0.3f;
    inputs.specular_roughness_anisotropy = 0.4f;
    const rmath::vec3 view = rmath::normalize(rmath::vec3(0.3f, -0.2f, 0.9f));
    const OpenPBR_PreparedBsdf prepared =
        openpbr_prepare(inputs, rmath::vec3(1.0f), OpenPBR_BaseRgbWavelengths_nm, OpenPBR_VacuumIor, view);
    double mean_weight = 0.0;
    const int count = 4096;
    for (int index = 0; index < count; ++index)
    {
        const rmath::vec3 u((float(index) + 0.5f) / float(count), rmath::fract(float(index) * 0.618034f),
                            rmath::fract(float(index) * 0.754878f));
        rmath::vec3 light;
        OpenPBR_DiffuseSpecular weight;
        float pdf = 0.0f;
        OpenPBR_BsdfLobeType sampled_type = 0u;
        openpbr_sample(prepared, u, light, weight, pdf, sampled_type);
        if (!(pdf > 0.0f))
        {
            continue;
        }
        const rmath::vec3 sum = openpbr_get_sum_of_diffuse_specular(weight);
        mean_weight += double(sum.y) / count;
        // The sample's weight is eval / pdf at its direction (continuous lobes), to float rounding.
        if ((sampled_type & OPENPBR_LOBE_TYPE_SPECULAR) == 0u)
        {
            const rmath::vec3 value = openpbr_get_sum_of_diffuse_specular(openpbr_eval(prepared, light));
            const float expected = value.y / openpbr_pdf(prepared, light);
            if (std::abs(expected - sum.y) > 1e-4f * std::max(1.0f, expected))
            {
                ++failures;
            }
        }
    }
    // Energy: the directional albedo of this material lies in (0, 1] (white-furnace bound).
    if (!(mean_weight > 0.05 && mean_weight <= 1.0))
    {
        ++failures;
    }
    std::printf("custom vector types: albedo estimate %.4f, %d failures\n", mean_weight, failures);
    return failures == 0 ? 0 : 1;
}
