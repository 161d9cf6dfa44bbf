// The public constants the Slang module exports under their own names (slang/openpbr.slang):
// OPENPBR_MODULE_CONSTANTS(X) calls X(type, NAME) for each, e.g. X(uint, OPENPBR_LOBE_TYPE_SPECULAR).
// Lobe-type flags and lobe ids (slang/lobes/openpbr_lobe_common.h), specialization-constant ids
// and feature bits (slang/openpbr_features.h), limits, table bindings and table layout
// (slang/openpbr_lut.h, slang/lobes/openpbr_fuzz_lobe.h), the working colour space and its two
// values (slang/openpbr_working_space.h). The values stay in those headers; this
// is only the list, shared by the module and its test (tests/targets/test_module_exports.cpp).
#ifndef OPENPBR_MODULE_CONSTANTS_H
#define OPENPBR_MODULE_CONSTANTS_H

#define OPENPBR_MODULE_CONSTANTS(X)                       \
    X(uint, OPENPBR_LOBE_TYPE_NONE)                       \
    X(uint, OPENPBR_LOBE_TYPE_REFLECTION)                 \
    X(uint, OPENPBR_LOBE_TYPE_TRANSMISSION)               \
    X(uint, OPENPBR_LOBE_TYPE_DIFFUSE)                    \
    X(uint, OPENPBR_LOBE_TYPE_GLOSSY)                     \
    X(uint, OPENPBR_LOBE_TYPE_SPECULAR)                   \
    X(uint, OPENPBR_LOBE_ID_SHIFT)                        \
    X(uint, OPENPBR_LOBE_ID_DIFFUSE)                      \
    X(uint, OPENPBR_LOBE_ID_SPECULAR_REFLECTION)          \
    X(uint, OPENPBR_LOBE_ID_METAL)                        \
    X(uint, OPENPBR_LOBE_ID_SPECULAR_TRANSMISSION)        \
    X(uint, OPENPBR_LOBE_ID_COAT)                         \
    X(uint, OPENPBR_LOBE_ID_FUZZ)                         \
    X(uint, OPENPBR_LOBE_ID_DIFFUSE_TRANSMISSION)         \
    X(uint, OPENPBR_LOBE_ID_INTERFACE_FROM_INSIDE)        \
    X(uint, OPENPBR_LOBE_ID_PASS_THROUGH)                 \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableCoat)         \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableFuzz)         \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableMetal)        \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableTransmission) \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableDispersion)   \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableThinFilm)     \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableThinWalled)   \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableSubsurface)   \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableEmission)     \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableAnisotropy)   \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableSheenAndCoat) \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableTranslucency) \
    X(uint, OPENPBR_SPECIALIZATION_ID_EnableMetallic)     \
    X(uint, OPENPBR_SPECIALIZATION_CONSTANT_COUNT)        \
    X(uint, OPENPBR_FEATURE_BIT_COAT)                     \
    X(uint, OPENPBR_FEATURE_BIT_FUZZ)                     \
    X(uint, OPENPBR_FEATURE_BIT_METAL)                    \
    X(uint, OPENPBR_FEATURE_BIT_TRANSMISSION)             \
    X(uint, OPENPBR_FEATURE_BIT_DISPERSION)               \
    X(uint, OPENPBR_FEATURE_BIT_THIN_FILM)                \
    X(uint, OPENPBR_FEATURE_BIT_THIN_WALLED)              \
    X(uint, OPENPBR_FEATURE_BIT_SUBSURFACE)               \
    X(uint, OPENPBR_FEATURE_BIT_EMISSION)                 \
    X(uint, OPENPBR_FEATURE_BIT_ANISOTROPY)               \
    X(uint, OPENPBR_FEATURE_MASK_ALL)                     \
    X(float, OPENPBR_DELTA_ALPHA_THRESHOLD)               \
    X(float, OPENPBR_MIN_LOBE_PROBABILITY)                \
    X(float, OPENPBR_LUT_MIN_VIEW_COSINE)                 \
    X(uint, OPENPBR_LUT_BINDING)                          \
    X(uint, OPENPBR_FUZZ_LTC_BINDING)                     \
    X(uint, OPENPBR_LUT_TEXTURE_BINDING)                  \
    X(uint, OPENPBR_LUT_2D_SIZE)                          \
    X(uint, OPENPBR_LUT_3D_SIZE)                          \
    X(uint, OPENPBR_LUT_3D_ETA_SIZE)                      \
    X(uint, OPENPBR_LUT_4D_SIZE)                          \
    X(uint, OPENPBR_LUT_4D_ANISOTROPY_SIZE)               \
    X(uint, OPENPBR_LUT_GGX_ALBEDO_OFFSET)                \
    X(uint, OPENPBR_LUT_DIELECTRIC_REFLECTION_OFFSET)     \
    X(uint, OPENPBR_LUT_DIELECTRIC_TRANSMISSION_OFFSET)   \
    X(uint, OPENPBR_LUT_DIELECTRIC_INTERFACE_OFFSET)      \
    X(uint, OPENPBR_LUT_GGX_ANISOTROPY_RATIO_OFFSET)      \
    X(uint, OPENPBR_LUT_TOTAL_COUNT)                      \
    X(uint, OPENPBR_FUZZ_LTC_SIZE)                        \
    X(uint, OPENPBR_FUZZ_LTC_TOTAL_COUNT)                 \
    X(uint, OPENPBR_WORKING_SPACE)                        \
    X(uint, OPENPBR_WORKING_SPACE_LIN_REC709)             \
    X(uint, OPENPBR_WORKING_SPACE_ACESCG)

#endif
