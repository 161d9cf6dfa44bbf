// material_fit.cpp - see material_fit.h.
#include "host/gradients/material_fit.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "host/scene/material_packing.h"
#include "host/scene/parameter_table.h"
#include "host/support/files.h"
#include "host/support/random.h"
#include "host/support/stopwatch.h"

namespace openpbr::host {

namespace {

using gradients::Direction;
using gradients::MaterialRecord;
using gradients::ValueRecord;

// The loss's floor under log(value), e.g. 1e-3: values far below it (a dark channel's diffuse
// floor) weigh little, and log never sees 0.
constexpr double log_floor = 1e-3;

// A FLOAT or COLOR input of the parameter table: its first packed slot, its float count, its range.
struct PackedInput
{
    std::size_t slot = 0;
    std::size_t count = 0;
    float low = 0.0f;
    float high = 0.0f;
};

bool find_packed_input(const std::string& name, PackedInput& found)
{
    std::size_t slot = 0;
    bool matched = false;
    auto visit = [&](const char* input, std::size_t count, float low, float high) {
        if (!matched && name == input)
        {
            found = {slot, count, low, high};
            matched = true;
        }
        slot += count;
    };
#define OPENPBR_FIT_FLOAT(field, default_value, low, high) visit(#field, 1, low, high);
#define OPENPBR_FIT_COLOR(field, default_r, default_g, default_b, low, high) visit(#field, 3, low, high);
#define OPENPBR_FIT_VECTOR2(field, default_x, default_y) slot += 2;
#define OPENPBR_FIT_BOOL(field, default_value) slot += 1;
#define OPENPBR_FIT_BASIS(field, normal_input, tangent_input) slot += 9;
    OPENPBR_PARAMETERS(OPENPBR_FIT_FLOAT, OPENPBR_FIT_COLOR, OPENPBR_FIT_VECTOR2, OPENPBR_FIT_BOOL, OPENPBR_FIT_BASIS)
#undef OPENPBR_FIT_FLOAT
#undef OPENPBR_FIT_COLOR
#undef OPENPBR_FIT_VECTOR2
#undef OPENPBR_FIT_BOOL
#undef OPENPBR_FIT_BASIS
    return matched;
}

[[noreturn]] void fail(const std::string& path, const std::string& what)
{
    throw std::runtime_error("fit case " + path + ": " + what);
}

std::vector<float> read_components(const nlohmann::json& value, std::size_t count, const std::string& path,
                                   const std::string& field)
{
    std::vector<float> components;
    if (count == 1 && value.is_number())
    {
        components.push_back(value.get<float>());
    }
    else if (value.is_array() && value.size() == count)
    {
        for (const nlohmann::json& component : value)
        {
            if (!component.is_number())
            {
                fail(path, field + ": expected numbers");
            }
            components.push_back(component.get<float>());
        }
    }
    else
    {
        fail(path, field + ": expected " + (count == 1 ? std::string("a number") : "an array of 3 numbers"));
    }
    return components;
}

// The true material: spec defaults with the case's "truth" inputs (any table input by name).
MaterialRecord read_truth(const nlohmann::json& truth, const std::string& path)
{
    OpenPBR_ResolvedInputs inputs = openpbr_make_default_resolved_inputs();
    if (!truth.is_object())
    {
        fail(path, "\"truth\" must be an object of inputs");
    }
    for (const auto& [name, value] : truth.items())
    {
        const ParameterDescriptor* descriptor = find_parameter(name);
        if (descriptor == nullptr)
        {
            fail(path, "truth: unknown input \"" + name + "\"");
        }
        if (const auto* field = std::get_if<float ParameterInputs::*>(&descriptor->target))
        {
            inputs.*(*field) = read_components(value, 1, path, "truth." + name)[0];
        }
        else if (const auto* color = std::get_if<glm::vec3 ParameterInputs::*>(&descriptor->target))
        {
            const std::vector<float> components = read_components(value, 3, path, "truth." + name);
            inputs.*(*color) = glm::vec3(components[0], components[1], components[2]);
        }
        else if (const auto* flag = std::get_if<bool ParameterInputs::*>(&descriptor->target); flag && value.is_boolean())
        {
            inputs.*(*flag) = value.get<bool>();
        }
        else
        {
            fail(path, "truth." + name + ": only float, colour and boolean inputs may be set");
        }
    }
    MaterialRecord record{};
    pack_material(inputs, record.data());
    return record;
}

template <typename T> T optional_value(const nlohmann::json& document, const char* key, T fallback)
{
    return document.contains(key) ? document.at(key).get<T>() : fallback;
}

// A direction on the unit hemisphere above (cosine-distributed for views, uniform for lights) or,
// for lights below too, on the whole sphere.
Direction cosine_direction(double u, double v)
{
    const double radius = std::sqrt(u);
    const double angle = 6.283185307179586 * v;
    return {float(radius * std::cos(angle)), float(radius * std::sin(angle)), float(std::sqrt(std::max(0.0, 1.0 - u)))};
}

Direction uniform_direction(double u, double v, bool whole_sphere)
{
    const double z = whole_sphere ? 1.0 - 2.0 * u : u;
    const double radius = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double angle = 6.283185307179586 * v;
    return {float(radius * std::cos(angle)), float(radius * std::sin(angle)), float(z)};
}

// A standard normal number (Box-Muller) from two uniform ones.
double normal_number(double u, double v) { return std::sqrt(-2.0 * std::log(1.0 - u)) * std::cos(6.283185307179586 * v); }

// The measurements grouped by view for the batched reverse pass, and each query's measurement.
std::vector<gradients::ViewQueries> group_by_view(const std::vector<Measurement>& measurements,
                                                  std::vector<std::size_t>& order)
{
    std::vector<gradients::ViewQueries> views;
    order.clear();
    for (std::size_t index = 0; index < measurements.size(); ++index)
    {
        if (views.empty() || views.back().view != measurements[index].view)
        {
            views.push_back({measurements[index].view, {}});
        }
        views.back().lights.push_back(measurements[index].light);
        order.push_back(index);
    }
    return views;
}

double log_value(double value) { return std::log(log_floor + std::max(value, 0.0)); }

}  // namespace

FitCase load_fit_case(const std::string& path)
{
    nlohmann::json document;
    try
    {
        document = nlohmann::json::parse(read_whole_file(path));
    }
    catch (const nlohmann::json::exception& error)
    {
        fail(path, std::string("not valid JSON: ") + error.what());
    }
    FitCase fit_case;
    fit_case.name = std::filesystem::path(path).stem().string();
    try
    {
        fit_case.description = optional_value<std::string>(document, "description", "");
        fit_case.truth = read_truth(document.value("truth", nlohmann::json::object()), path);
        const nlohmann::json& measurements = document.at("measurements");
        fit_case.views = optional_value<std::size_t>(measurements, "views", fit_case.views);
        fit_case.lights_per_view = optional_value<std::size_t>(measurements, "lights_per_view", fit_case.lights_per_view);
        fit_case.lights_below = optional_value<bool>(measurements, "lights_below", fit_case.lights_below);
        fit_case.noise = optional_value<float>(measurements, "noise", fit_case.noise);
        fit_case.seed = optional_value<unsigned>(measurements, "seed", fit_case.seed);
        fit_case.iterations = optional_value<std::size_t>(document, "iterations", fit_case.iterations);
        fit_case.learning_rate = optional_value<float>(document, "learning_rate", fit_case.learning_rate);
        for (const auto& [name, entry] : document.at("fit").items())
        {
            PackedInput input;
            if (!find_packed_input(name, input))
            {
                fail(path, "fit: \"" + name + "\" is not a float or colour input");
            }
            FitParameter parameter;
            parameter.name = name;
            parameter.slot = input.slot;
            parameter.count = input.count;
            parameter.start = read_components(entry.at("start"), input.count, path, "fit." + name + ".start");
            parameter.tolerance = entry.at("tolerance").get<float>();
            // The fit's range: the parameter's, narrowed where the case says (e.g. an IOR in [1, 3]).
            parameter.low = std::max(input.low, optional_value<float>(entry, "low", input.low));
            parameter.high = std::min(input.high, optional_value<float>(entry, "high", input.high));
            for (std::size_t component = 0; component < input.count; ++component)
            {
                parameter.truth.push_back(fit_case.truth[input.slot + component]);
            }
            fit_case.parameters.push_back(parameter);
        }
    }
    catch (const nlohmann::json::exception& error)
    {
        fail(path, std::string("missing or malformed field: ") + error.what());
    }
    if (fit_case.parameters.empty() || fit_case.views == 0 || fit_case.lights_per_view == 0)
    {
        fail(path, "nothing to fit (\"fit\" empty, or no measurements)");
    }
    return fit_case;
}

std::vector<Measurement> make_measurements(const FitCase& fit_case)
{
    std::vector<Measurement> measurements;
    SplitMix64 random{splitmix64(fit_case.seed)};
    OpenPBR_ResolvedInputs truth = openpbr_make_default_resolved_inputs();
    {
        // The packed record back into inputs (openpbr_unpack_material's expansion, as the kernels do).
        const float* record = fit_case.truth.data();
        std::size_t index = 0;
        auto next = [&]() { return record[index++]; };
#define OPENPBR_FIT_UNPACK_FLOAT(field, default_value, low, high) truth.field = next();
#define OPENPBR_FIT_UNPACK_COLOR(field, default_r, default_g, default_b, low, high) \
    truth.field.x = next();                                                         \
    truth.field.y = next();                                                         \
    truth.field.z = next();
#define OPENPBR_FIT_UNPACK_VECTOR2(field, default_x, default_y) \
    truth.field.x = next();                                     \
    truth.field.y = next();
#define OPENPBR_FIT_UNPACK_BOOL(field, default_value) truth.field = next() != 0.0f;
#define OPENPBR_FIT_UNPACK_BASIS(field, normal_input, tangent_input)                                                    \
    for (int vector = 0; vector < 3; ++vector)                                                                          \
    {                                                                                                                   \
        glm::vec3& part = vector == 0 ? truth.field.tangent : vector == 1 ? truth.field.bitangent : truth.field.normal; \
        part.x = next();                                                                                                \
        part.y = next();                                                                                                \
        part.z = next();                                                                                                \
    }
        OPENPBR_PARAMETERS(OPENPBR_FIT_UNPACK_FLOAT, OPENPBR_FIT_UNPACK_COLOR, OPENPBR_FIT_UNPACK_VECTOR2,
                           OPENPBR_FIT_UNPACK_BOOL, OPENPBR_FIT_UNPACK_BASIS)
#undef OPENPBR_FIT_UNPACK_FLOAT
#undef OPENPBR_FIT_UNPACK_COLOR
#undef OPENPBR_FIT_UNPACK_VECTOR2
#undef OPENPBR_FIT_UNPACK_BOOL
#undef OPENPBR_FIT_UNPACK_BASIS
    }
    for (std::size_t view_index = 0; view_index < fit_case.views; ++view_index)
    {
        const double u = random.next_double();
        const Direction view = cosine_direction(u, random.next_double());
        const glm::vec3 view_vector(view[0], view[1], view[2]);
        const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(truth, view_vector);
        for (std::size_t light_index = 0; light_index < fit_case.lights_per_view; ++light_index)
        {
            Measurement measurement;
            measurement.view = view;
            const double light_u = random.next_double();
            measurement.light = uniform_direction(light_u, random.next_double(), fit_case.lights_below);
            const OpenPBR_DiffuseSpecular value =
                openpbr_eval(bsdf, glm::vec3(measurement.light[0], measurement.light[1], measurement.light[2]));
            for (int channel = 0; channel < 3; ++channel)
            {
                const double noise_u = random.next_double();
                const double noise = fit_case.noise * normal_number(noise_u, random.next_double());
                measurement.value[channel] = float((value.diffuse[channel] + value.specular[channel]) * (1.0 + noise));
            }
            measurements.push_back(measurement);
        }
    }
    return measurements;
}

std::vector<std::string> fit_component_names(const FitCase& fit_case)
{
    std::vector<std::string> names;
    const char* channels[] = {".r", ".g", ".b"};
    for (const FitParameter& parameter : fit_case.parameters)
    {
        for (std::size_t component = 0; component < parameter.count; ++component)
        {
            names.push_back(parameter.name + (parameter.count == 3 ? channels[component] : ""));
        }
    }
    return names;
}

FitResult fit_material(const FitCase& fit_case, const std::vector<Measurement>& measurements)
{
    const Stopwatch stopwatch;
    std::vector<std::size_t> order;
    const std::vector<gradients::ViewQueries> views = group_by_view(measurements, order);
    const double channel_count = 3.0 * double(measurements.size());
    MaterialRecord material = fit_case.truth;
    // Each component: its slot, its range; Adam's moments.
    struct Component
    {
        std::size_t slot;
        float low;
        float high;
        double first_moment = 0.0;
        double second_moment = 0.0;
    };
    std::vector<Component> components;
    for (const FitParameter& parameter : fit_case.parameters)
    {
        for (std::size_t component = 0; component < parameter.count; ++component)
        {
            material[parameter.slot + component] = std::clamp(parameter.start[component], parameter.low, parameter.high);
            components.push_back({parameter.slot + component, parameter.low, parameter.high});
        }
    }
    auto values_of = [&]() {
        std::vector<float> values;
        for (const Component& component : components)
        {
            values.push_back(material[component.slot]);
        }
        return values;
    };
    // Adam (Kingma and Ba 2015, Algorithm 1) with beta1 0.9, beta2 0.999, epsilon 1e-8 and the step
    // scaled by each component's range; the rate falls along a half cosine to a tenth at the end,
    // so the last iterations settle instead of orbiting the minimum at the noise's scale.
    constexpr double beta1 = 0.9;
    constexpr double beta2 = 0.999;
    FitResult result;
    for (std::size_t iteration = 0; iteration <= fit_case.iterations; ++iteration)
    {
        std::vector<double> losses(measurements.size(), 0.0);
        const gradients::CotangentFunction cotangent_of = [&](std::size_t query, const ValueRecord& value) {
            const Measurement& measured = measurements[order[query]];
            ValueRecord cotangent{};
            double loss = 0.0;
            for (int channel = 0; channel < 3; ++channel)
            {
                const double modelled =
                    double(value[gradients::value_diffuse + channel]) + double(value[gradients::value_specular + channel]);
                const double difference = log_value(modelled) - log_value(measured.value[channel]);
                loss += difference * difference;
                // d/d(modelled) of difference^2 / channel_count; 0 where the value is clamped at 0.
                const double slope = modelled > 0.0 ? 2.0 * difference / ((log_floor + modelled) * channel_count) : 0.0;
                cotangent[gradients::value_diffuse + channel] = float(slope);
                cotangent[gradients::value_specular + channel] = float(slope);
            }
            losses[order[query]] = loss;
            return cotangent;
        };
        const MaterialRecord gradient = gradients::batch_reverse(material, views, cotangent_of, nullptr);
        double loss = 0.0;
        for (const double part : losses)
        {
            loss += part;
        }
        result.history.push_back({iteration, loss / channel_count, values_of()});
        if (iteration == fit_case.iterations)
        {
            break;
        }
        const double progress = double(iteration) / double(std::max<std::size_t>(fit_case.iterations, 1));
        const double rate = fit_case.learning_rate * (0.55 + 0.45 * std::cos(3.141592653589793 * progress));
        const double t = double(iteration + 1);
        for (Component& component : components)
        {
            const double g = gradient[component.slot];
            component.first_moment = beta1 * component.first_moment + (1.0 - beta1) * g;
            component.second_moment = beta2 * component.second_moment + (1.0 - beta2) * g * g;
            const double first = component.first_moment / (1.0 - std::pow(beta1, t));
            const double second = component.second_moment / (1.0 - std::pow(beta2, t));
            const double step = rate * double(component.high - component.low) * first / (std::sqrt(second) + 1e-8);
            material[component.slot] =
                std::clamp(float(double(material[component.slot]) - step), component.low, component.high);
        }
    }
    result.fitted = values_of();
    result.within_tolerance = true;
    std::size_t index = 0;
    for (const FitParameter& parameter : fit_case.parameters)
    {
        for (std::size_t component = 0; component < parameter.count; ++component, ++index)
        {
            if (!(std::fabs(result.fitted[index] - parameter.truth[component]) <= parameter.tolerance))
            {
                result.within_tolerance = false;
            }
        }
    }
    result.seconds = stopwatch.seconds();
    return result;
}

std::string fit_history_csv(const FitCase& fit_case, const FitResult& result)
{
    std::ostringstream csv;
    csv << "iteration,loss";
    for (const std::string& name : fit_component_names(fit_case))
    {
        csv << "," << name;
    }
    // The second row holds the truth (no iteration, no loss), for the plot's reference lines.
    csv << "\ntruth,";
    for (const FitParameter& parameter : fit_case.parameters)
    {
        for (const float value : parameter.truth)
        {
            csv << "," << value;
        }
    }
    csv << "\n";
    for (const FitStep& step : result.history)
    {
        csv << step.iteration << "," << step.loss;
        for (const float value : step.values)
        {
            csv << "," << value;
        }
        csv << "\n";
    }
    return csv.str();
}

}  // namespace openpbr::host
