// double_reference.cpp - see double_reference.h. Compiled against the double-precision copy of the
// headers (CMake: the include path puts build/double-headers before the repository), in a
// namespace of its own, with its own names for the compiled-in tables (as
// host/studies/accuracy_double_variant.cpp does: one name cannot have two types).
#include "tests/autodiff/double_reference.h"

#include <stdexcept>
#include <string>

#define openpbr_lut_data autodiff_double_lut_data
#define openpbr_fuzz_ltc_data autodiff_double_fuzz_ltc_data
#define OPENPBR_CPP_VARIANT_NAMESPACE autodiff_double
#include "slang/openpbr.h"

namespace {
// The record being unpacked (one query at a time per thread).
thread_local const double* unpacked_record = nullptr;
}  // namespace

#define OPENPBR_MATERIAL_UNPACK_NAME openpbr_autodiff_double_unpack
#define OPENPBR_MATERIAL_UNPACK_READ(index) unpacked_record[index]
#include "slang/openpbr_material_packing.h"
#include "targets/autodiff/openpbr_gradient_records.h"

static_assert(sizeof(openpbr::autodiff_double::OpenPBR_DiffuseSpecular{}.diffuse.x) == sizeof(double),
              "the double-precision headers must come first on this translation unit's include path");
static_assert(OPENPBR_PACKED_MATERIAL_FLOATS == openpbr::test::double_material_floats, "the packed record's size");
static_assert(OPENPBR_GRADIENT_VALUE_FLOATS == openpbr::test::double_value_floats, "the value record's size");

namespace openpbr::test {

namespace {

namespace reference = openpbr::autodiff_double;

reference::OpenPBR_PreparedBsdf prepare(const DoubleMaterial& material, const DoubleDirection& view)
{
    unpacked_record = material.data();
    const reference::OpenPBR_ResolvedInputs inputs = reference::openpbr_autodiff_double_unpack(0u);
    unpacked_record = nullptr;
    return reference::openpbr_prepare(inputs, glm::dvec3(view[0], view[1], view[2]));
}

// The prepared field `field` (OPENPBR_GRADIENT_PREPARED_FIELDS' order) of a prepared BSDF.
glm::dvec3& prepared_field(reference::OpenPBR_PreparedBsdf& bsdf, std::size_t field)
{
    std::size_t index = 0;
#define OPENPBR_DOUBLE_FIELD(name) \
    if (index++ == field)          \
    {                              \
        return bsdf.name;          \
    }
    OPENPBR_GRADIENT_PREPARED_FIELDS(OPENPBR_DOUBLE_FIELD)
#undef OPENPBR_DOUBLE_FIELD
    throw std::out_of_range("no prepared field " + std::to_string(field));
}

}  // namespace

DoubleValue double_query_value(const DoubleMaterial& material, const DoubleDirection& view, const DoubleDirection& light,
                               const PreparedFieldStep* prepared)
{
    reference::OpenPBR_PreparedBsdf bsdf = prepare(material, view);
    if (prepared != nullptr)
    {
        prepared_field(bsdf, prepared->field)[int(prepared->channel)] += prepared->step;
    }
    const glm::dvec3 light_direction(light[0], light[1], light[2]);
    const reference::OpenPBR_DiffuseSpecular value = reference::openpbr_eval(bsdf, light_direction);
    DoubleValue record{};
    for (int channel = 0; channel < 3; ++channel)
    {
        record[OPENPBR_GRADIENT_VALUE_DIFFUSE + channel] = value.diffuse[channel];
        record[OPENPBR_GRADIENT_VALUE_SPECULAR + channel] = value.specular[channel];
        record[OPENPBR_GRADIENT_VALUE_EMISSION + channel] = bsdf.emission[channel];
    }
    record[OPENPBR_GRADIENT_VALUE_PDF] = reference::openpbr_pdf(bsdf, light_direction);
    return record;
}

double double_prepared_field(const DoubleMaterial& material, const DoubleDirection& view, std::size_t field,
                             std::size_t channel)
{
    reference::OpenPBR_PreparedBsdf bsdf = prepare(material, view);
    return prepared_field(bsdf, field)[int(channel)];
}

std::size_t double_prepared_field_count()
{
    std::size_t count = 0;
#define OPENPBR_DOUBLE_COUNT(name) ++count;
    OPENPBR_GRADIENT_PREPARED_FIELDS(OPENPBR_DOUBLE_COUNT)
#undef OPENPBR_DOUBLE_COUNT
    return count;
}

const char* double_prepared_field_name(std::size_t field)
{
    static const char* const names[] = {
#define OPENPBR_DOUBLE_NAME(name) #name,
        OPENPBR_GRADIENT_PREPARED_FIELDS(OPENPBR_DOUBLE_NAME)
#undef OPENPBR_DOUBLE_NAME
    };
    return field < double_prepared_field_count() ? names[field] : "";
}

}  // namespace openpbr::test
