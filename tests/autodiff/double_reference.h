// double_reference.h - the BSDF in double precision (tools/make_double_headers.py's copy of the
// headers, compiled by double_reference.cpp), the reference the gradient tests take central
// differences of: one query's value record (targets/autodiff/openpbr_gradient_records.h layout)
// from a packed material record in doubles.
#pragma once

#include <array>
#include <cstddef>

namespace openpbr::test {

inline constexpr std::size_t double_material_floats = 80;  // OPENPBR_PACKED_MATERIAL_FLOATS
inline constexpr std::size_t double_value_floats = 10;     // OPENPBR_GRADIENT_VALUE_FLOATS

using DoubleMaterial = std::array<double, double_material_floats>;
using DoubleValue = std::array<double, double_value_floats>;
using DoubleDirection = std::array<double, 3>;

// openpbr_prepare(unpacked material, view) (air, default wavelengths), then eval, pdf and the
// emission, as targets/autodiff/gradients.slang differentiates them.
DoubleValue double_query_value(const DoubleMaterial& material, const DoubleDirection& view, const DoubleDirection& light);

}  // namespace openpbr::test
