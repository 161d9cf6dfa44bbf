// gradient_check.h - what the gradient tests share: the corpus of queries (every lobe alone, every
// bundled material, the stability corpus's hard cases with finite inputs, named special points),
// the parameters checked (every float and colour slot of the packed record, and the view and light
// directions), and the comparison of a derivative with one-sided and central differences of the
// double-precision build (double_reference.h), which tells a smooth point from a kink (where the
// derivative must equal the difference on one side) and from a jump (a singular point, counted
// and not compared).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>  // first: the OpenPBR headers require it (interop/openpbr_interop_cpp.h)
#include "host/gradients/gradients.h"
#include "slang/openpbr_resolved_inputs.h"
#include "tests/autodiff/double_reference.h"

namespace openpbr::test {

// One query: a material (packed record) and its view and light (world space, unit length).
struct GradientQuery
{
    std::string label;              // e.g. "Glass reflection"
    OpenPBR_ResolvedInputs inputs;  // the material, unpacked
    host::gradients::MaterialRecord material{};
    host::gradients::Direction view{};
    host::gradients::Direction light{};
};

// One checked input: a slot of the packed record (its parameter's range), or a direction component.
struct CheckedInput
{
    enum class Kind
    {
        material,
        view,
        light,
        prepared  // a channel of a prepared field between prepare and eval (index: field * 3 + channel)
    };
    Kind kind = Kind::material;
    std::size_t index = 0;  // slot or component
    std::string name;       // e.g. "base_color.g", "view.z"
    double low = -1e30;     // the parameter's range (the input contract's clamp); directions unbounded
    double high = 1e30;
};

// Every FLOAT and COLOR slot of the parameter table, then the view's and the light's components.
std::vector<CheckedInput> checked_inputs();

// The scalar a reverse pass differentiates: dot(weights, value record).
using ValueWeights = host::gradients::ValueRecord;
// The three checked scalars: eval (diffuse and specular, channels weighted differently), the
// emission, the pdf.
std::vector<std::pair<std::string, ValueWeights>> checked_scalars();

// The corpora.
std::vector<GradientQuery> lobe_queries();                                    // Default, EveryLobe, Only/* and Without/*
std::vector<GradientQuery> bundled_material_queries(const std::string& dir);  // every materials/*.mtlx
std::vector<GradientQuery> special_point_queries();                           // zero weights, range ends, roughness 0
// The stability corpus's cases away from its degenerate points (gradient_check.cpp says which:
// float extremes, grazing directions, a lobe collapsed to a line), in air.
std::vector<GradientQuery> stability_corpus_queries(const std::string& path);

// Whether a derivative that the differences find singular (a jump within the step) is at one of
// the documented singular points (docs/gradients.md, "The domain"): the switch between the back
// of an opaque material and the inside of a translucent one where the entering weight
// (1 - metalness)(T + (1 - T) S) reaches 0, for a view below the surface; specular_weight 0,
// where the modulated IOR moves like sqrt(specular_weight); any direction component (critical
// angles, the film estimate's segment switches, a mirror lobe's delta threshold); the inputs that
// move the film's critical cosine where a mirror's film sits at it (at_film_critical_cosine); and
// a view within float rounding of a table's critical-cosine kink (documented_rounding_kink).
bool documented_singular_point(const GradientQuery& query, const CheckedInput& input);

// Whether the query's base is a mirror whose thin film, evaluated at the view's cosine, sits
// within float rounding of the film's critical cosine sqrt(1 - (n_f / n_o)^2) (n_o the coat's
// IOR blended by coat_weight, n_f thin_film_ior): there the film's reflectance goes like the
// square root of the distance to it (docs/gradients.md, "Jumps"), so the inputs that move the
// critical cosine (coat_ior, coat_weight, thin_film_ior) have no derivative, and float rounding
// of the cosine moves the float code's values (film_critical_tolerance in test_gradients.cpp).
bool at_film_critical_cosine(const GradientQuery& query);

// Whether an infinite one-sided derivative is of the documented kind (docs/gradients.md, "The
// domain"): a material input at an end of its range, where the value goes like the square root
// of the distance to it (e.g. a thin film over a metal of colour 0).
bool documented_unbounded_point(const GradientQuery& query, const CheckedInput& input);

// Whether the query's view lies within float rounding of a kink that a 3D table look-up of the
// base has at its view cosine (docs/gradients.md, "The domain"): the view cosine of the base's
// frame within 2.4e-7 (4 float ulps of a cosine near 1) of the critical cosine of one of the
// base's relative IORs (per channel), where the tables' view axis changes its slope and has a
// node (openpbr_lut_plain_view_coordinate, openpbr_lut_view_coordinate). The float gradient
// code and the double build may round to different sides of it.
bool documented_rounding_kink(const GradientQuery& query);

// The outcome of comparing one derivative with the differences of the double build.
enum class Agreement
{
    smooth,       // matched the central difference at a point where both sides agree
    one_sided,    // a kink (or a range end): matched the difference on one side
    across_kink,  // a kink within float rounding of the point (documented_rounding_kink): matched
                  // the chord beyond it on one side
    singular,     // a jump within the step on both sides, or a kink within float rounding of the point
                  // whose far side no chord reaches: not compared
    unbounded,    // an infinite one-sided derivative (differences growing like step^(-1/2)): not compared
    failed
};

struct Comparison
{
    Agreement agreement = Agreement::failed;
    double reference = 0.0;  // the difference it was compared with (central or one-sided)
    double error = 0.0;      // |derivative - reference| / (relative + absolute tolerance), <= 1 passes
};

// Tolerances of the comparison: |derivative - reference| <= relative |reference| + absolute scale,
// scale = max(|scalar|, scale_floor) (see test_gradients.cpp for the measured figures).
struct Tolerance
{
    double relative = 0.0;
    double absolute = 0.0;
    double scale_floor = 0.0;
};

// Compares `derivative` (of `scalar` with respect to `input`, at the query) with differences of the
// double build.
Comparison compare_with_differences(const GradientQuery& query, const ValueWeights& scalar, const CheckedInput& input,
                                    double derivative, const Tolerance& tolerance);

// The scalar dot(weights, value) of the double build at the query with one input moved by `step`.
double double_scalar(const GradientQuery& query, const ValueWeights& scalar, const CheckedInput& input, double step);

// The reverse-mode derivative of the scalar with respect to the input, from a gradient.
double derivative_of(const host::gradients::QueryGradient& gradient, const CheckedInput& input);

}  // namespace openpbr::test
