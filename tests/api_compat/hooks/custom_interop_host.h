// A renderer's own interop layer for the BSDF (OPENPBR_USE_CUSTOM_INTEROP=1): its own namespace
// (renderer_bsdf rather than openpbr), its own feature switches behind
// OPENPBR_GET_SPECIALIZATION_CONSTANT (the coarse toggle names included), GLM as the vector
// library. interop/openpbr_interop.h then includes no backend of its own.
#ifndef CUSTOM_INTEROP_HOST_H
#define CUSTOM_INTEROP_HOST_H

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#define OPENPBR_USE_CUSTOM_INTEROP 1
#define OPENPBR_LANGUAGE_TARGET_CPP 1

// The renderer's switches: bit = OPENPBR_SPECIALIZATION_ID_<name>, e.g. the coarse
// EnableSheenAndCoat (id 10) turns coat and fuzz off together.
namespace renderer {
inline std::uint32_t enabled_features = 0xffffffffu;
}

#define OPENPBR_NAMESPACE_BEGIN \
    namespace renderer_bsdf {   \
    using namespace glm;        \
    typedef unsigned int uint;
#define OPENPBR_NAMESPACE_END }
#define OPENPBR_FUNC inline
#define OPENPBR_IN(type) const type&
#define OPENPBR_INOUT(type) type&
#define OPENPBR_OUT(type) type&
#define OPENPBR_UNUSED(name) (void)(name)
#define OPENPBR_GLOBAL_CONSTANT inline const
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name)
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) \
    (((::renderer::enabled_features >> OPENPBR_SPECIALIZATION_ID_##name) & 1u) != 0u)

namespace renderer_bsdf {
inline float atan2(float y, float x) { return std::atan2(y, x); }
inline float saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
inline glm::vec3 saturate(const glm::vec3& v) { return glm::clamp(v, glm::vec3(0.0f), glm::vec3(1.0f)); }
}  // namespace renderer_bsdf

#endif
