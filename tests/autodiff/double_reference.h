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

// A step on one channel of one prepared field (OPENPBR_GRADIENT_PREPARED_FIELDS' order), applied
// between prepare and eval: what the GPU's prepared kernel differentiates with respect to.
struct PreparedFieldStep
{
    std::size_t field = 0;    // e.g. 0: diffuse.single_scatter_a
    std::size_t channel = 0;  // 0-2
    double step = 0.0;
};

// openpbr_prepare(unpacked material, view) (air, default wavelengths), then eval, pdf and the
// emission, as targets/autodiff/gradients.slang differentiates them; with `prepared`, that field
// of the prepared BSDF moved by its step before eval and pdf.
DoubleValue double_query_value(const DoubleMaterial& material, const DoubleDirection& view, const DoubleDirection& light,
                               const PreparedFieldStep* prepared = nullptr);

// The value of one prepared field's channel after prepare.
double double_prepared_field(const DoubleMaterial& material, const DoubleDirection& view, std::size_t field,
                             std::size_t channel);

// How many fields OPENPBR_GRADIENT_PREPARED_FIELDS lists, and their names (e.g. "metal.weight").
std::size_t double_prepared_field_count();
const char* double_prepared_field_name(std::size_t field);

}  // namespace openpbr::test
