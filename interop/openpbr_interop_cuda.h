// CUDA backend: GLM compiled for host and device (GLM adds __host__ __device__ itself
// under nvcc), so the CUDA build is the C++ build with device qualifiers.
#ifndef OPENPBR_INTEROP_CUDA_H
#define OPENPBR_INTEROP_CUDA_H

#include <cuda_runtime.h>
#if !(defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES)
// As in C++ (openpbr_interop_cpp.h): the host includes <glm/glm.hpp> first.
#if !defined(GLM_VERSION)
#error \
    "OpenPBR (CUDA): include <glm/glm.hpp> before the OpenPBR headers, or define OPENPBR_USE_CUSTOM_VEC_TYPES=1 and provide vec2/vec3/vec4 and their math functions"
#endif
#include <glm/glm.hpp>
#define OPENPBR_CUDA_USE_VECTOR_LIBRARY using namespace glm;
#else
#define OPENPBR_CUDA_USE_VECTOR_LIBRARY
#endif

#define OPENPBR_NAMESPACE_BEGIN     \
    namespace openpbr {             \
    OPENPBR_CUDA_USE_VECTOR_LIBRARY \
    typedef unsigned int uint;
#define OPENPBR_NAMESPACE_END }

#define OPENPBR_FUNC __host__ __device__ inline
// A part of a larger function, called once (interop/openpbr_interop_cpp.h): inlined.
#define OPENPBR_INLINE_FUNC __host__ __device__ __forceinline__
#define OPENPBR_IN(type) const type&
#define OPENPBR_INOUT(type) type&
// Marks a parameter a lobe ignores (the shared lobe signature has it), e.g. the view of a
// Lambertian pdf; C-family compilers would otherwise warn.
#define OPENPBR_UNUSED(name) (void)(name)
#define OPENPBR_OUT(type) type&

// Feature toggles (slang/openpbr_features.h): CUDA has no specialization constants, so the
// toggles are compile-time permutations, e.g. nvcc -DOPENPBR_FEATURE_COAT=0; all on otherwise.
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name)
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) true

// Program-scope constants (e.g. OpenPBR_VacuumIor) live in device memory, initialized at
// compile time: device code reads them; host code uses the C++ build's copies.
#define OPENPBR_GLOBAL_CONSTANT __device__ const
// Loops kept rolled (openpbr_interop.h): nvcc's pragma in the device pass only (the host
// compiler rejects it, and CPU code keeps its own choice).
#ifdef __CUDA_ARCH__
#define OPENPBR_DONT_UNROLL _Pragma("unroll 1")
#endif

namespace openpbr {
__host__ __device__ inline float atan2(float y, float x) { return ::atan2f(y, x); }
#if !(defined(OPENPBR_USE_CUSTOM_SATURATE) && OPENPBR_USE_CUSTOM_SATURATE) && \
    !(defined(OPENPBR_USE_CUSTOM_VEC_TYPES) && OPENPBR_USE_CUSTOM_VEC_TYPES)
// HLSL's saturate, which the dialect uses; OPENPBR_USE_CUSTOM_SATURATE=1 when the host has one.
__host__ __device__ inline float saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
template <glm::length_t L, glm::qualifier Q>
__host__ __device__ inline glm::vec<L, float, Q> saturate(const glm::vec<L, float, Q>& v)
{
    return glm::clamp(v, glm::vec<L, float, Q>(0.0f), glm::vec<L, float, Q>(1.0f));
}
#endif
}  // namespace openpbr

#endif
