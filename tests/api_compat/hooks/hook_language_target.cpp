// Backend selection of interop/openpbr_interop.h, compiled as C++ once per case
// (tests/api_compat/CMakeLists.txt) with the compiler-macro it detects or the explicit
// OPENPBR_LANGUAGE_TARGET_* it must obey, and EXPECT_<TARGET> naming the backend it must pick.
// OPENPBR_USE_CUSTOM_INTEROP=1 keeps the chosen backend's own header out (Metal's or CUDA's
// would not compile here), so only the selection is under test; the real backends are
// compiled by the api_compat builds of each language.
#define OPENPBR_USE_CUSTOM_INTEROP 1
#define OPENPBR_NAMESPACE_BEGIN
#define OPENPBR_NAMESPACE_END
#define OPENPBR_FUNC inline
#define OPENPBR_IN(type) const type&
#define OPENPBR_INOUT(type) type&
#define OPENPBR_OUT(type) type&
#define OPENPBR_UNUSED(name) (void)(name)
#define OPENPBR_DECLARE_SPECIALIZATION_CONSTANT(name)
#define OPENPBR_GET_SPECIALIZATION_CONSTANT(name) true
#include "interop/openpbr_interop.h"

#if defined(EXPECT_CPP) && (!defined(OPENPBR_LANGUAGE_TARGET_CPP) || defined(OPENPBR_LANGUAGE_TARGET_CUDA) || \
                            defined(OPENPBR_LANGUAGE_TARGET_METAL))
#error "expected the C++ backend"
#endif
#if defined(EXPECT_CUDA) && (!defined(OPENPBR_LANGUAGE_TARGET_CUDA) || defined(OPENPBR_LANGUAGE_TARGET_CPP))
#error "expected the CUDA backend"
#endif
#if defined(EXPECT_METAL) && (!defined(OPENPBR_LANGUAGE_TARGET_METAL) || !defined(OPENPBR_LANGUAGE_TARGET_MSL) || \
                              defined(OPENPBR_LANGUAGE_TARGET_CPP))
#error "expected the Metal backend (OPENPBR_LANGUAGE_TARGET_MSL and _METAL both set)"
#endif
#if defined(EXPECT_GLSL) && (!defined(OPENPBR_LANGUAGE_TARGET_GLSL) || defined(OPENPBR_LANGUAGE_TARGET_CPP))
#error "expected the GLSL backend"
#endif
#if defined(EXPECT_SLANG) && (!defined(OPENPBR_LANGUAGE_TARGET_SLANG) || defined(OPENPBR_LANGUAGE_TARGET_CPP))
#error "expected the Slang backend"
#endif
#if !defined(EXPECT_CPP) && !defined(EXPECT_CUDA) && !defined(EXPECT_METAL) && !defined(EXPECT_GLSL) && \
    !defined(EXPECT_SLANG)
#error "define one EXPECT_<TARGET>"
#endif

int main() { return 0; }
