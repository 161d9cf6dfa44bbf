// CUDA backend: GLM compiled for host and device (GLM adds __host__ __device__ itself
// under nvcc), so the CUDA build is the C++ build with device qualifiers.
#ifndef OPENPBR_INTEROP_CUDA_H
#define OPENPBR_INTEROP_CUDA_H

#include <cuda_runtime.h>
#include <glm/glm.hpp>

#define OPENPBR_NAMESPACE_BEGIN \
    namespace openpbr {         \
    using namespace glm;        \
    typedef unsigned int uint;
#define OPENPBR_NAMESPACE_END }

#define OPENPBR_FUNC __host__ __device__ inline
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

namespace openpbr {
__host__ __device__ inline float atan2(float y, float x) { return ::atan2f(y, x); }
}  // namespace openpbr

#endif
