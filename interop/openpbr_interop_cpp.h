// C++ backend (host and CPU reference build): the dialect maps onto GLM.
// Everything lives in namespace openpbr so vec3 & co. do not leak into user code.
#ifndef OPENPBR_INTEROP_CPP_H
#define OPENPBR_INTEROP_CPP_H

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#define OPENPBR_NAMESPACE_BEGIN \
    namespace openpbr {         \
    using namespace glm;        \
    typedef unsigned int uint;
#define OPENPBR_NAMESPACE_END }

// Header-only: every function is inline; structs go by const reference to avoid copies.
#define OPENPBR_FUNC inline
#define OPENPBR_IN(type) const type&
#define OPENPBR_INOUT(type) type&
// Marks a parameter a lobe ignores (the shared lobe signature has it), e.g. the view of a
// Lambertian pdf; C-family compilers would otherwise warn.
#define OPENPBR_UNUSED(name) (void)(name)
#define OPENPBR_OUT(type) type&

namespace openpbr {
// GLSL has atan(y, x); the dialect spells it atan2 so Slang/HLSL/Metal need no wrapper.
inline float atan2(float y, float x) { return std::atan2(y, x); }
}  // namespace openpbr

#endif
