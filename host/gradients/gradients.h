// gradients.h - gradients of the BSDF on the CPU by Slang's automatic differentiation of the
// module itself: Slang's C++ output of targets/autodiff/gradients.slang (the differentiable
// build, OPENPBR_AUTODIFF=1), compiled into the library openpbr_gradients (docs/gradients.md).
// A material is its packed record (host/scene/material_packing.h: one float per slot, in the
// parameter table's order), so a material's gradient is one float per slot; what is
// differentiated is a query's value record (targets/autodiff/openpbr_gradient_records.h): eval's
// diffuse and specular parts toward the light, the emission towards the view and the pdf of the
// light, of openpbr_prepare(material, view) in air with the default wavelengths.
//
// Stack: the generated code keeps a reverse pass's intermediates in locals, several MiB of them
// (prepare's reverse pass needed more than the 8 MiB default), so every call runs on a thread of
// its own with a large stack (run_on_large_stack; batch_reverse runs its workers that way).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace openpbr::host::gradients {

inline constexpr std::size_t material_floats = 80;  // OPENPBR_PACKED_MATERIAL_FLOATS (checked in gradients.cpp)
inline constexpr std::size_t value_floats = 10;     // OPENPBR_GRADIENT_VALUE_FLOATS
inline constexpr std::size_t value_diffuse = 0;     // offsets in a value record
inline constexpr std::size_t value_specular = 3;
inline constexpr std::size_t value_emission = 6;
inline constexpr std::size_t value_pdf = 9;

using MaterialRecord = std::array<float, material_floats>;
using ValueRecord = std::array<float, value_floats>;
using Direction = std::array<float, 3>;

// Derivatives of a scalar with respect to the material's slots and the two directions (world
// space, as given: the view is normalized by prepare, the light is taken as it is).
struct QueryGradient
{
    MaterialRecord material{};
    Direction view{};
    Direction light{};
};

// The value record of one query.
ValueRecord query_value(const MaterialRecord& material, const Direction& view, const Direction& light);

// Reverse mode: the value, and in `gradient` the gradient of sum_i cotangent[i] value[i].
ValueRecord query_reverse(const MaterialRecord& material, const Direction& view, const Direction& light,
                          const ValueRecord& cotangent, QueryGradient& gradient);

// Forward mode: the value, and in `derivative` its derivative along the tangent (material_tangent,
// view_tangent, light_tangent).
ValueRecord query_forward(const MaterialRecord& material, const MaterialRecord& material_tangent, const Direction& view,
                          const Direction& view_tangent, const Direction& light, const Direction& light_tangent,
                          ValueRecord& derivative);

// Many lights per view, e.g. a fit's measurements: the queries (view, lights[j]) of each entry.
struct ViewQueries
{
    Direction view{};
    std::vector<Direction> lights;
};

// The cotangent of a query from its value, e.g. the derivative of a loss with respect to the value
// record; `query` numbers the queries in order (every light of the first view, then the next).
using CotangentFunction = std::function<ValueRecord(std::size_t query, const ValueRecord& value)>;

// The material gradient of sum over queries of dot(cotangent_of(query, value), value), with one
// prepare and one reverse pass of prepare per view (eval's and pdf's reverse passes summed into
// the prepared BSDF's differential first). `values` (if given) receives every query's value.
// Views are shared among up to `threads` workers (0: the hardware's count); cotangent_of may be
// called from any of them, once per query.
MaterialRecord batch_reverse(const MaterialRecord& material, const std::vector<ViewQueries>& views,
                             const CotangentFunction& cotangent_of, std::vector<ValueRecord>* values, unsigned threads = 0);

// Runs `work` on a thread whose stack holds the generated code's reverse passes (64 MiB) and
// waits for it; exceptions are passed on.
void run_on_large_stack(const std::function<void()>& work);

}  // namespace openpbr::host::gradients
