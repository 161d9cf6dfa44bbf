// The C++ parameter table: see parameter_table.h.
#include "host/scene/parameter_table.h"

namespace openpbr::host {

const std::vector<ParameterBasis>& parameter_bases()
{
#define OPENPBR_BASIS_SKIP_FLOAT(name, default_value, low, high)
#define OPENPBR_BASIS_SKIP_COLOR(name, default_r, default_g, default_b, low, high)
#define OPENPBR_BASIS_SKIP_VECTOR2(name, default_x, default_y)
#define OPENPBR_BASIS_SKIP_BOOL(name, default_value)
#define OPENPBR_BASIS_ENTRY(name, normal_input, tangent_input) {&ParameterInputs::name, #normal_input, #tangent_input},
    static const std::vector<ParameterBasis> bases = {OPENPBR_PARAMETERS(OPENPBR_BASIS_SKIP_FLOAT, OPENPBR_BASIS_SKIP_COLOR,
                                                                         OPENPBR_BASIS_SKIP_VECTOR2, OPENPBR_BASIS_SKIP_BOOL,
                                                                         OPENPBR_BASIS_ENTRY)};
#undef OPENPBR_BASIS_SKIP_FLOAT
#undef OPENPBR_BASIS_SKIP_COLOR
#undef OPENPBR_BASIS_SKIP_VECTOR2
#undef OPENPBR_BASIS_SKIP_BOOL
#undef OPENPBR_BASIS_ENTRY
    return bases;
}

const std::vector<ParameterDescriptor>& parameter_descriptors()
{
    static const std::vector<ParameterDescriptor> descriptors = [] {
        std::vector<ParameterDescriptor> list;
        std::size_t basis = 0;
#define OPENPBR_DESCRIBE_FLOAT(name, default_value, low, high) list.push_back({#name, &ParameterInputs::name, true});
#define OPENPBR_DESCRIBE_COLOR(name, default_r, default_g, default_b, low, high) \
    list.push_back({#name, &ParameterInputs::name, true});
#define OPENPBR_DESCRIBE_VECTOR2(name, default_x, default_y) list.push_back({#name, &ParameterInputs::name, false});
#define OPENPBR_DESCRIBE_BOOL(name, default_value) list.push_back({#name, &ParameterInputs::name, true});
#define OPENPBR_DESCRIBE_BASIS(name, normal_input, tangent_input)        \
    list.push_back({#normal_input, GeometryVector{basis, false}, true}); \
    list.push_back({#tangent_input, GeometryVector{basis, true}, true}); \
    ++basis;
        OPENPBR_PARAMETERS(OPENPBR_DESCRIBE_FLOAT, OPENPBR_DESCRIBE_COLOR, OPENPBR_DESCRIBE_VECTOR2, OPENPBR_DESCRIBE_BOOL,
                           OPENPBR_DESCRIBE_BASIS)
#undef OPENPBR_DESCRIBE_FLOAT
#undef OPENPBR_DESCRIBE_COLOR
#undef OPENPBR_DESCRIBE_VECTOR2
#undef OPENPBR_DESCRIBE_BOOL
#undef OPENPBR_DESCRIBE_BASIS
        return list;
    }();
    return descriptors;
}

const ParameterDescriptor* find_parameter(const std::string_view name)
{
    for (const ParameterDescriptor& descriptor : parameter_descriptors())
    {
        if (name == descriptor.name)
        {
            return &descriptor;
        }
    }
    return nullptr;
}

}  // namespace openpbr::host
