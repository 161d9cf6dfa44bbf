// layered_reference.cpp - see layered_reference.h. Double precision; the model's float headers
// only for the input contract (the reference reads the same clamped inputs as the model).
#include "host/references/layered_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "host/support/random.h"
#include "host/support/stopwatch.h"
#include "host/tables/fuzz_fit.h"
#include "slang/openpbr.h"

namespace openpbr::host {
namespace {

constexpr double pi = 3.14159265358979323846;
// A path is stopped (counted as absorbed, and reported) after this many component events, e.g.
// 100000: lossless stacks lose nothing to it in practice (the longest path of the checks' white
// coat over white metal at roughness 1 took a few hundred events).
constexpr int max_events = 100000;
// Russian roulette below this largest channel weight, e.g. 0.01: a path survives with
// probability max weight / threshold and carries its weight divided by that (unbiased).
constexpr double roulette_threshold = 0.01;
// Flake events after which a path in the fuzz is stopped (as the fuzz fit's walks are), e.g.
// 100000; a unit-thickness layer of optical depth at most 1 per unit length leaves after a few.
constexpr int fuzz_max_events = 100000;

double luminance(const LayeredColor& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
double largest(const LayeredColor& c) { return std::max(c[0], std::max(c[1], c[2])); }
LayeredColor multiply(const LayeredColor& a, const LayeredColor& b) { return {a[0] * b[0], a[1] * b[1], a[2] * b[2]}; }
LayeredColor to_color(const glm::vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// A cosine-distributed direction about +z.
glm::dvec3 cosine_direction(double u1, double u2)
{
    const double radius = std::sqrt(u1);
    const double phi = 2.0 * pi * u2;
    return glm::dvec3(radius * std::cos(phi), radius * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1)));
}

// ---- Fresnel factors of the base interface ----

class F82Fresnel final : public MicrosurfaceFresnel
{
  public:
    F82Fresnel(const LayeredColor& f0_value, const LayeredColor& edge_value) : f0(f0_value), edge_tint(edge_value) {}
    MicrosurfaceColor reflectance(double cos_incident, bool) const override
    {
        return layered_f82_fresnel(f0, edge_tint, cos_incident);
    }

  private:
    LayeredColor f0;
    LayeredColor edge_tint;
};

class FilmOverConductorFresnel final : public MicrosurfaceFresnel
{
  public:
    FilmOverConductorFresnel(double n_outside_value, double n_film_value, const LayeredColor& f0_value,
                             const LayeredColor& edge_value, double thickness_value)
        : n_outside(n_outside_value), n_film(n_film_value), f0(f0_value), edge_tint(edge_value),
          thickness_um(thickness_value)
    {
    }
    MicrosurfaceColor reflectance(double cos_incident, bool) const override
    {
        return layered_film_over_conductor(cos_incident, n_outside, n_film, f0, edge_tint, thickness_um);
    }

  private:
    double n_outside;
    double n_film;
    LayeredColor f0;
    LayeredColor edge_tint;
    double thickness_um;
};

// The film over a dielectric: the Airy reflectance from the outer side; from the inner side the
// same at the outer cosine of the same ray (a lossless stack transmits, hence reflects, the same
// from both sides), 1 beyond the critical angle.
class FilmOverDielectricFresnel final : public MicrosurfaceFresnel
{
  public:
    FilmOverDielectricFresnel(double n_outer_value, double n_film_value, double n_inner_value, double thickness_value,
                              bool outer_up_value)
        : n_outer(n_outer_value), n_film(n_film_value), n_inner(n_inner_value), thickness_um(thickness_value),
          outer_up(outer_up_value)
    {
    }
    MicrosurfaceColor reflectance(double cos_incident, bool from_above) const override
    {
        double cos_outer = cos_incident;
        if (from_above != outer_up)
        {
            const double ratio = n_inner / n_outer;
            const double sin_squared = ratio * ratio * (1.0 - cos_incident * cos_incident);
            if (sin_squared >= 1.0)
            {
                return {1.0, 1.0, 1.0};
            }
            cos_outer = std::sqrt(1.0 - sin_squared);
        }
        return layered_film_over_dielectric(cos_outer, n_outer, n_film, n_inner, thickness_um);
    }

  private:
    double n_outer;
    double n_film;
    double n_inner;
    double thickness_um;
    bool outer_up;
};

// ---- Stack construction ----

struct StackChoice
{
    bool fuzz = false;
    bool coat = false;
    int base = 0;  // 0 metal, 1 translucent, 2 subsurface, 3 glossy-diffuse
    bool film = false;
};

const char* base_name(int base)
{
    static const char* names[] = {"metal", "translucent", "subsurface", "glossy-diffuse"};
    return names[base];
}

LayeredComponent make_interface(const std::string& name, double roughness, double anisotropy, double eta,
                                MicrosurfaceResponse response, std::shared_ptr<const MicrosurfaceFresnel> fresnel)
{
    LayeredComponent component;
    component.kind = LayeredComponentKind::interface;
    component.name = name;
    const std::array<double, 2> alpha = layered_ggx_alpha(roughness, anisotropy);
    component.interface.alpha_x = alpha[0];
    component.interface.alpha_y = alpha[1];
    component.interface.eta = eta;
    component.interface.response = response;
    component.fresnel = std::move(fresnel);
    component.interface.fresnel = component.fresnel.get();
    return component;
}

// The component as seen in the structure mirrored about the base (thin-walled): upside down.
LayeredComponent mirrored(const LayeredComponent& component, const OpenPBR_ResolvedInputs& inputs, double n_outer,
                          double n_inner)
{
    LayeredComponent copy = component;
    copy.name = component.name + " (mirrored)";
    if (component.kind == LayeredComponentKind::interface)
    {
        copy.interface.eta = 1.0 / component.interface.eta;
        copy.outer_side_up = !component.outer_side_up;
        if (component.fresnel != nullptr)
        {
            // Only the base's dielectric carries a Fresnel object on a thin-walled translucent
            // or subsurface stack: the film over the sheet, seen from below.
            copy.fresnel = std::make_shared<FilmOverDielectricFresnel>(n_outer, double(inputs.thin_film_ior), n_inner,
                                                                       double(inputs.thin_film_thickness), false);
        }
        copy.interface.fresnel = copy.fresnel.get();
    }
    return copy;
}

double channel_value(const LayeredColor& color, int channel) { return color[std::size_t(channel)]; }

LayeredStack build_stack(const OpenPBR_ResolvedInputs& inputs, const StackChoice& choice, int channel, double weight,
                         const LayeredBuildOptions& options, std::uint64_t stack_seed)
{
    LayeredStack stack;
    stack.weight = weight;
    stack.name = std::string(choice.fuzz ? "fuzz + " : "") + (choice.coat ? "coat + " : "") + base_name(choice.base) +
                 (choice.film ? " + film" : "");
    std::vector<LayeredComponent> above_base;
    if (choice.fuzz)
    {
        LayeredComponent fuzz;
        fuzz.kind = LayeredComponentKind::fuzz;
        fuzz.name = "fuzz";
        fuzz.cross_section = fuzz_cross_section_from_roughness(double(inputs.fuzz_roughness));
        above_base.push_back(fuzz);
        stack.fuzz_tint = to_color(inputs.fuzz_color);
    }
    double n_above = 1.0;
    if (choice.coat)
    {
        const double coat_ior = double(inputs.coat_ior);
        above_base.push_back(make_interface("coat interface", double(inputs.coat_roughness),
                                            double(inputs.coat_roughness_anisotropy), coat_ior,
                                            MicrosurfaceResponse::reflect_or_refract, nullptr));
        LayeredComponent absorber;
        absorber.kind = LayeredComponentKind::absorber;
        absorber.name = "coat medium";
        for (int c = 0; c < 3; ++c)
        {
            // coat_color is the normal-incidence round trip: ln T per pass = ln(coat_color) / 2.
            absorber.log_transmittance[std::size_t(c)] =
                0.5 * std::log(std::max(double(inputs.coat_color[c]), std::numeric_limits<double>::min()));
        }
        above_base.push_back(absorber);
        n_above = coat_ior;
    }
    const double roughness = double(inputs.specular_roughness);
    const double anisotropy = double(inputs.specular_roughness_anisotropy);
    const bool thin_walled = inputs.geometry_thin_walled;
    stack.components = above_base;
    if (choice.base == 0)
    {
        const LayeredColor f0 =
            multiply(to_color(inputs.base_color),
                     {double(inputs.base_weight), double(inputs.base_weight), double(inputs.base_weight)});
        const LayeredColor edge = to_color(inputs.specular_color);
        std::shared_ptr<const MicrosurfaceFresnel> fresnel;
        if (choice.film)
        {
            fresnel = std::make_shared<FilmOverConductorFresnel>(n_above, double(inputs.thin_film_ior), f0, edge,
                                                                 double(inputs.thin_film_thickness));
        }
        else
        {
            fresnel = std::make_shared<F82Fresnel>(f0, edge);
        }
        LayeredComponent metal =
            make_interface("metal", roughness, anisotropy, 1.0, MicrosurfaceResponse::reflect, std::move(fresnel));
        const double scale = std::min(double(inputs.specular_weight), 1.0);
        metal.per_hit_scale = {scale, scale, scale};
        stack.components.push_back(metal);
        return stack;
    }
    // The dielectric base: relative IOR against what lies above it, modulated by specular_weight,
    // dispersive where the material is (per channel), clamped to the model's IOR range.
    const double relative =
        std::clamp(double(inputs.specular_ior) / n_above, double(OPENPBR_IOR_MIN), double(OPENPBR_IOR_MAX));
    const double modulated = layered_modulated_ior(relative, double(inputs.specular_weight));
    const double eta =
        channel_value(layered_dispersive_ior(modulated, double(inputs.transmission_dispersion_abbe_number),
                                             thin_walled ? 0.0 : double(inputs.transmission_dispersion_scale)),
                      channel);
    const double n_below = eta * n_above;
    std::shared_ptr<const MicrosurfaceFresnel> fresnel;
    if (choice.film)
    {
        fresnel = std::make_shared<FilmOverDielectricFresnel>(n_above, double(inputs.thin_film_ior), n_below,
                                                              double(inputs.thin_film_thickness), true);
    }
    LayeredComponent dielectric = make_interface("dielectric interface", roughness, anisotropy, eta,
                                                 MicrosurfaceResponse::reflect_or_refract, std::move(fresnel));
    dielectric.reflect_outer_tint = to_color(inputs.specular_color);
    if (choice.base == 1 && !thin_walled && !(inputs.transmission_depth > 0.0f))
    {
        dielectric.enter_tint = to_color(inputs.transmission_color);
    }
    stack.components.push_back(dielectric);
    if (choice.base == 3)
    {
        LayeredComponent diffuse;
        diffuse.kind = LayeredComponentKind::diffuse;
        diffuse.name = "diffuse";
        diffuse.rho =
            layered_calibrate_diffuse(dielectric, to_color(inputs.base_color), options.calibration_paths, stack_seed);
        diffuse.sigma = double(inputs.base_diffuse_roughness);
        diffuse.weight = double(inputs.base_weight);
        stack.components.push_back(diffuse);
        return stack;
    }
    if (!thin_walled)
    {
        return stack;  // the interior lies below: what crosses is transmitted
    }
    LayeredComponent sheet;
    if (choice.base == 1)
    {
        sheet.kind = LayeredComponentKind::absorber;
        sheet.name = "thin-walled sheet medium";
        for (int c = 0; c < 3; ++c)
        {
            sheet.log_transmittance[std::size_t(c)] =
                std::log(std::max(double(inputs.transmission_color[c]), std::numeric_limits<double>::min()));
        }
    }
    else
    {
        sheet.kind = LayeredComponentKind::sheet;
        sheet.name = "thin-walled scattering sheet";
        const double g = double(inputs.subsurface_scatter_anisotropy);
        for (int c = 0; c < 3; ++c)
        {
            const double color = double(inputs.subsurface_color[c]);
            sheet.sheet_reflection[std::size_t(c)] = 0.5 * color * (1.0 - g);
            sheet.sheet_transmission[std::size_t(c)] = 0.5 * color * (1.0 + g);
        }
        sheet.sigma = double(inputs.base_diffuse_roughness);
    }
    stack.components.push_back(sheet);
    // The mirror image below the sheet: the base interface, then the coat and the fuzz, upside down.
    stack.components.push_back(mirrored(dielectric, inputs, n_above, n_below));
    for (auto it = above_base.rbegin(); it != above_base.rend(); ++it)
    {
        stack.components.push_back(mirrored(*it, inputs, n_above, n_below));
    }
    return stack;
}

std::string describe_stacks(const std::vector<LayeredStack>& stacks)
{
    std::string text;
    for (const LayeredStack& stack : stacks)
    {
        char buffer[96];
        std::snprintf(buffer, sizeof(buffer), "%s%.3g %s", text.empty() ? "" : " + ", stack.weight, stack.name.c_str());
        text += buffer;
    }
    return text;
}

}  // namespace

LayeredColor layered_calibrate_diffuse(const LayeredComponent& interface, const LayeredColor& color, std::uint64_t paths,
                                       std::uint64_t seed)
{
    SplitMix64 random{splitmix64(seed)};
    LayeredColor reflected{0.0, 0.0, 0.0};
    LayeredColor entered{0.0, 0.0, 0.0};
    LayeredColor escaped{0.0, 0.0, 0.0};
    for (std::uint64_t path = 0; path < paths; ++path)
    {
        // Normal incidence from above: E_spec (tinted) and T_in.
        const MicrosurfaceScattering down = microsurface_scatter(interface.interface, glm::dvec3(0.0, 0.0, -1.0), 0, random);
        // Lambertian light from below (stratified over cos^2 theta): tau.
        const double u = (double(path) + random.next_double()) / double(paths);
        const glm::dvec3 up = cosine_direction(u, random.next_double());
        const MicrosurfaceScattering out = microsurface_scatter(interface.interface, up, 0, random);
        for (std::size_t c = 0; c < 3; ++c)
        {
            if (!down.absorbed)
            {
                (down.transmitted ? entered[c] : reflected[c]) +=
                    down.weight[c] * (down.transmitted ? 1.0 : interface.reflect_outer_tint[c]);
            }
            if (!out.absorbed && out.transmitted)
            {
                escaped[c] += out.weight[c];
            }
        }
    }
    LayeredColor rho{0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < 3; ++c)
    {
        const double n = double(paths);
        const double e_spec = reflected[c] / n;
        const double t_in = entered[c] / n;
        const double tau = escaped[c] / n;
        const double target = t_in > 0.0 ? color[c] * (1.0 - e_spec) / t_in : color[c];
        const double denominator = tau + target * (1.0 - tau);
        rho[c] = denominator > 0.0 ? std::clamp(target / denominator, 0.0, 1.0) : 0.0;
    }
    return rho;
}

LayeredMaterial layered_material_from_inputs(const OpenPBR_ResolvedInputs& raw_inputs, const LayeredBuildOptions& options)
{
    const OpenPBR_ResolvedInputs inputs = openpbr_prepare_inputs(raw_inputs);
    LayeredMaterial material;
    const double opacity = double(inputs.geometry_opacity);
    const double fuzz = double(inputs.fuzz_weight);
    const double coat = double(inputs.coat_weight);
    const double metal = double(inputs.base_metalness);
    const double translucent = double(inputs.transmission_weight);
    const double subsurface = double(inputs.subsurface_weight);
    const double film = double(inputs.thin_film_weight);
    const double base_weights[4] = {metal, (1.0 - metal) * translucent, (1.0 - metal) * (1.0 - translucent) * subsurface,
                                    (1.0 - metal) * (1.0 - translucent) * (1.0 - subsurface)};
    material.per_channel =
        !inputs.geometry_thin_walled && inputs.transmission_dispersion_scale > 0.0f && metal < 1.0 && translucent > 0.0;
    const int channel_sets = material.per_channel ? 3 : 1;
    for (int channel = 0; channel < channel_sets; ++channel)
    {
        std::vector<LayeredStack>& stacks = material.stacks[std::size_t(channel)];
        if (opacity < 1.0)
        {
            LayeredStack pass;
            pass.name = "pass-through";
            pass.weight = 1.0 - opacity;
            pass.pass_through = true;
            stacks.push_back(pass);
        }
        std::uint64_t index = 0;
        for (int with_fuzz = 0; with_fuzz < 2; ++with_fuzz)
        {
            for (int with_coat = 0; with_coat < 2; ++with_coat)
            {
                for (int base = 0; base < 4; ++base)
                {
                    for (int with_film = 0; with_film < 2; ++with_film)
                    {
                        ++index;
                        const double weight = opacity * (with_fuzz ? fuzz : 1.0 - fuzz) * (with_coat ? coat : 1.0 - coat) *
                                              base_weights[base] * (with_film ? film : 1.0 - film);
                        if (!(weight > 0.0))
                        {
                            continue;
                        }
                        const StackChoice choice{with_fuzz == 1, with_coat == 1, base, with_film == 1};
                        stacks.push_back(build_stack(inputs, choice, channel, weight, options,
                                                     options.seed + 7919 * index + 104729 * channel));
                    }
                }
            }
        }
    }
    material.description = describe_stacks(material.stacks[0]);
    if (material.per_channel)
    {
        material.description += " (per channel: dispersive)";
    }
    return material;
}

// ---- The walk ----

namespace {

struct FuzzExit
{
    bool top = false;
    bool capped = false;
    glm::dvec3 direction{0.0, 0.0, 0.0};
};

// The fuzz volume (z in [-1, 0], host/tables/fuzz_fit.h's simulate_fuzz_layer with both faces
// open): free flights of extinction sigma(w), specular flake reflections, until it leaves.
FuzzExit fuzz_walk(double cross_section, const glm::dvec3& travel, SplitMix64& random)
{
    FuzzExit exit;
    glm::dvec3 direction = travel;
    double z = travel.z < 0.0 ? 0.0 : -1.0;
    for (int event = 0; event < fuzz_max_events; ++event)
    {
        const double sigma = fuzz_sggx_projected_area(direction, cross_section);
        const double distance = -std::log(1.0 - random.next_double()) / sigma;
        const double z_next = z + distance * direction.z;
        if (z_next > 0.0 || z_next < -1.0)
        {
            exit.top = z_next > 0.0;
            exit.direction = direction;
            return exit;
        }
        z = z_next;
        const double u1 = random.next_double();
        const double u2 = random.next_double();
        direction = fuzz_phase_sample(-direction, cross_section, u1, u2);
    }
    exit.capped = true;
    return exit;
}

// An EON-shaped scattering from a diffuse component or the sheet: a cosine-distributed
// direction on the side `up`, weight f cos / pdf for EON of albedo rho (f cos from
// layered_eon_value with view and light mirrored to the upper side).
glm::dvec3 eon_scatter(const LayeredColor& rho, double sigma, const glm::dvec3& arrival, bool up, SplitMix64& random,
                       LayeredColor& weight)
{
    const double u1 = random.next_double();
    const double u2 = random.next_double();
    const glm::dvec3 local = cosine_direction(u1, u2);
    // The view (towards where light came from) on the upper side of the lobe's frame.
    const glm::dvec3 view(-arrival.x, -arrival.y, std::abs(arrival.z));
    const LayeredColor value = layered_eon_value(rho, sigma, view, local);
    const double pdf = local.z / pi;
    for (std::size_t c = 0; c < 3; ++c)
    {
        weight[c] = pdf > 0.0 ? value[c] / pdf : 0.0;
    }
    return glm::dvec3(local.x, local.y, up ? local.z : -local.z);
}

}  // namespace

LayeredExit layered_trace(const LayeredStack& stack, const glm::dvec3& view, SplitMix64& random)
{
    LayeredExit exit;
    if (stack.pass_through)
    {
        exit.left = true;
        exit.direction = -view;
        exit.weight = {1.0, 1.0, 1.0};
        return exit;
    }
    const int count = int(stack.components.size());
    const bool has_fuzz = count > 0 && stack.components[0].kind == LayeredComponentKind::fuzz;
    int gap = 0;  // gap i lies above component i; gap `count` is the interior
    glm::dvec3 travel = -view;
    LayeredColor weight{1.0, 1.0, 1.0};
    bool below_fuzz = false;
    for (int event = 0; event < max_events; ++event)
    {
        if (!(travel.z != 0.0))
        {
            return exit;  // a grazing direction never meets the next component
        }
        const bool down = travel.z < 0.0;
        if (!down && gap == 0)
        {
            exit.left = true;
            exit.direction = travel;
            exit.weight = has_fuzz && !below_fuzz ? multiply(weight, stack.fuzz_tint) : weight;
            return exit;
        }
        if (down && gap == count)
        {
            exit.left = true;
            exit.direction = travel;
            exit.weight = weight;
            return exit;
        }
        const int index = down ? gap : gap - 1;
        const LayeredComponent& component = stack.components[std::size_t(index)];
        switch (component.kind)
        {
        case LayeredComponentKind::fuzz:
        {
            const FuzzExit out = fuzz_walk(component.cross_section, travel, random);
            if (out.capped)
            {
                exit.capped = true;
                return exit;
            }
            travel = out.direction;
            gap = out.top ? index : index + 1;
            below_fuzz = below_fuzz || (index == 0 && !out.top);
            break;
        }
        case LayeredComponentKind::absorber:
            for (std::size_t c = 0; c < 3; ++c)
            {
                weight[c] *= std::exp(component.log_transmittance[c] / std::abs(travel.z));
            }
            gap = down ? index + 1 : index;
            break;
        case LayeredComponentKind::interface:
        {
            const MicrosurfaceScattering out = microsurface_scatter(component.interface, travel, 0, random);
            if (out.absorbed)
            {
                return exit;
            }
            const bool from_outer = down == component.outer_side_up;
            const LayeredColor& tint = out.transmitted ? component.enter_tint : component.reflect_outer_tint;
            for (std::size_t c = 0; c < 3; ++c)
            {
                weight[c] *= out.weight[c] * component.per_hit_scale[c] * (from_outer ? tint[c] : 1.0);
            }
            travel = out.direction;
            const bool now_down = travel.z < 0.0;
            gap = now_down ? index + 1 : index;
            break;
        }
        case LayeredComponentKind::diffuse:
        {
            if (!down)
            {
                return exit;  // an opaque diffuse is lit from above only
            }
            LayeredColor factor{0.0, 0.0, 0.0};
            travel = eon_scatter(component.rho, component.sigma, travel, true, random, factor);
            for (std::size_t c = 0; c < 3; ++c)
            {
                weight[c] *= factor[c] * component.weight;
            }
            gap = index;
            break;
        }
        case LayeredComponentKind::sheet:
        {
            // Reflect back to the side light came from, or transmit, chosen by luminance.
            const double reflect_share = luminance(component.sheet_reflection);
            const double transmit_share = luminance(component.sheet_transmission);
            if (!(reflect_share + transmit_share > 0.0))
            {
                return exit;
            }
            const double p_transmit = transmit_share / (reflect_share + transmit_share);
            const bool transmits = random.next_double() < p_transmit;
            const bool up = transmits != down;  // reflection goes back up when light came down
            LayeredColor factor{0.0, 0.0, 0.0};
            travel = eon_scatter({1.0, 1.0, 1.0}, component.sigma, travel, up, random, factor);
            const LayeredColor& albedo = transmits ? component.sheet_transmission : component.sheet_reflection;
            const double probability = transmits ? p_transmit : 1.0 - p_transmit;
            for (std::size_t c = 0; c < 3; ++c)
            {
                weight[c] *= factor[c] * albedo[c] / probability;
            }
            gap = up ? index : index + 1;
            break;
        }
        }
        const double strongest = largest(weight);
        if (!(strongest > 0.0))
        {
            return exit;
        }
        if (strongest < roulette_threshold)
        {
            const double survival = strongest / roulette_threshold;
            if (random.next_double() >= survival)
            {
                return exit;
            }
            for (double& value : weight)
            {
                value /= survival;
            }
        }
    }
    exit.capped = true;
    return exit;
}

LayeredExit layered_trace_material(const LayeredMaterial& material, const glm::dvec3& view, SplitMix64& random)
{
    const int set = material.per_channel ? std::min(int(random.next_double() * 3.0), 2) : 0;
    const std::vector<LayeredStack>& stacks = material.stacks[std::size_t(set)];
    double u = random.next_double();
    std::size_t chosen = 0;
    for (; chosen + 1 < stacks.size(); ++chosen)
    {
        if (u < stacks[chosen].weight)
        {
            break;
        }
        u -= stacks[chosen].weight;
    }
    if (stacks.empty())
    {
        return {};
    }
    LayeredExit exit = layered_trace(stacks[chosen], view, random);
    if (material.per_channel)
    {
        for (int c = 0; c < 3; ++c)
        {
            exit.weight[std::size_t(c)] = c == set ? 3.0 * exit.weight[std::size_t(c)] : 0.0;
        }
    }
    return exit;
}

// ---- Estimates ----

double LayeredGrid::bin_solid_angle() const { return 2.0 * pi / double(bins_per_hemisphere()); }

int LayeredGrid::bin_of(const glm::dvec3& direction) const
{
    if (!(direction.z != 0.0) || !(std::abs(direction.z) <= 1.0 + 1e-9))
    {
        return -1;
    }
    const int hemisphere = direction.z > 0.0 ? 0 : 1;
    const double r = std::sqrt(std::max(0.0, 1.0 - std::abs(direction.z)));  // Lambert: area pi r^2 = solid angle / 2
    double angle = std::atan2(direction.y, direction.x);                     // (-pi, pi]
    if (angle < -0.25 * pi)
    {
        angle += 2.0 * pi;  // [-pi/4, 7 pi/4): the four wedges of the concentric map
    }
    // The inverse concentric map: wedge by wedge, the radius is the square's larger coordinate
    // and the angle within the wedge is linear in the other one.
    double a = 0.0;
    double b = 0.0;
    const double scale = 4.0 / pi;
    if (angle < 0.25 * pi)
    {
        a = r;
        b = r * angle * scale;
    }
    else if (angle < 0.75 * pi)
    {
        b = r;
        a = r * (0.5 * pi - angle) * scale;
    }
    else if (angle < 1.25 * pi)
    {
        a = -r;
        b = -r * (angle - pi) * scale;
    }
    else
    {
        b = -r;
        a = -r * (1.5 * pi - angle) * scale;
    }
    const int i = std::clamp(int((a + 1.0) * 0.5 * resolution), 0, resolution - 1);
    const int j = std::clamp(int((b + 1.0) * 0.5 * resolution), 0, resolution - 1);
    return hemisphere * bins_per_hemisphere() + j * resolution + i;
}

glm::dvec3 LayeredGrid::bin_direction(int bin, double u, double v) const
{
    const int hemisphere = bin / bins_per_hemisphere();
    const int within = bin % bins_per_hemisphere();
    const double a = (double(within % resolution) + u) / resolution * 2.0 - 1.0;
    const double b = (double(within / resolution) + v) / resolution * 2.0 - 1.0;
    // The concentric map (Shirley & Chiu 1997).
    double r = 0.0;
    double angle = 0.0;
    if (std::abs(a) > std::abs(b))
    {
        r = a;
        angle = 0.25 * pi * (b / a);
    }
    else if (b != 0.0)
    {
        r = b;
        angle = 0.5 * pi - 0.25 * pi * (a / b);
    }
    const double mu = 1.0 - r * r;
    const double sine = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    return glm::dvec3(sine * std::cos(angle) * (r < 0.0 ? -1.0 : 1.0), sine * std::sin(angle) * (r < 0.0 ? -1.0 : 1.0),
                      hemisphere == 0 ? mu : -mu);
}

namespace {

// Sums of one stack's path weights: totals, per hemisphere and per bin, per channel.
struct StackSums
{
    std::uint64_t paths = 0;
    LayeredColor total{}, total_squares{}, reflected{}, reflected_squares{}, transmitted{}, transmitted_squares{};
    double luminance_sum = 0.0, luminance_squares = 0.0;
    std::vector<LayeredColor> bins, bin_squares;

    explicit StackSums(int bin_count)
        : bins(std::size_t(bin_count), LayeredColor{}), bin_squares(std::size_t(bin_count), LayeredColor{})
    {
    }

    void add(const LayeredExit& exit, int bin, int only_channel)
    {
        ++paths;
        if (!exit.left)
        {
            return;
        }
        LayeredColor value = exit.weight;
        if (only_channel >= 0)
        {
            for (int c = 0; c < 3; ++c)
            {
                value[std::size_t(c)] = c == only_channel ? value[std::size_t(c)] : 0.0;
            }
        }
        const bool up = exit.direction.z > 0.0;
        for (std::size_t c = 0; c < 3; ++c)
        {
            const double v = value[c];
            total[c] += v;
            total_squares[c] += v * v;
            (up ? reflected : transmitted)[c] += v;
            (up ? reflected_squares : transmitted_squares)[c] += v * v;
            if (bin >= 0)
            {
                bins[std::size_t(bin)][c] += v;
                bin_squares[std::size_t(bin)][c] += v * v;
            }
        }
        const double l = luminance(value);
        luminance_sum += l;
        luminance_squares += l * l;
    }
};

// Mean and variance of the mean from a sum and a sum of squares over n samples.
void mean_and_variance(double sum, double squares, std::uint64_t n, double& mean, double& variance)
{
    const double count = double(std::max<std::uint64_t>(n, 1));
    mean = sum / count;
    variance = n > 1 ? std::max(squares / count - mean * mean, 0.0) / (count - 1.0) : 0.0;
}

// Paths per stack: by weight, each non-trivial stack at least 1/16 of the total, one for a pass-through.
std::vector<std::uint64_t> allocate_paths(const std::vector<LayeredStack>& stacks, std::uint64_t paths)
{
    double walked_weight = 0.0;
    for (const LayeredStack& stack : stacks)
    {
        walked_weight += stack.pass_through ? 0.0 : stack.weight;
    }
    std::vector<std::uint64_t> counts;
    for (const LayeredStack& stack : stacks)
    {
        const double share = walked_weight > 0.0 ? stack.weight / walked_weight : 0.0;
        counts.push_back(stack.pass_through ? 1
                                            : std::max<std::uint64_t>(std::uint64_t(std::ceil(share * double(paths))),
                                                                      std::max<std::uint64_t>(paths / 16, 2)));
    }
    return counts;
}

}  // namespace

LayeredEstimate estimate_layered(const LayeredMaterial& material, double mu, const LayeredGrid& grid, std::uint64_t paths,
                                 std::uint64_t seed)
{
    if (!(mu > 0.0 && mu <= 1.0) || paths == 0)
    {
        throw std::invalid_argument("estimate_layered: view cosine must be in (0, 1] and paths > 0");
    }
    const Stopwatch watch;
    const ThreadCpuStopwatch cpu_watch;
    const glm::dvec3 view(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
    const int bin_count = grid.bin_count();
    const double inverse_solid_angle = 1.0 / grid.bin_solid_angle();
    LayeredEstimate estimate;
    estimate.bins.assign(std::size_t(bin_count), LayeredColor{});
    estimate.bin_errors.assign(std::size_t(bin_count), LayeredColor{});
    std::vector<LayeredColor> bin_variances(std::size_t(bin_count), LayeredColor{});
    LayeredColor variance_total{}, variance_reflected{}, variance_transmitted{};
    double luminance_variance = 0.0;
    const int channel_sets = material.per_channel ? 3 : 1;
    for (int set = 0; set < channel_sets; ++set)
    {
        const std::vector<LayeredStack>& stacks = material.stacks[std::size_t(set)];
        const std::vector<std::uint64_t> counts = allocate_paths(stacks, paths);
        const int only_channel = material.per_channel ? set : -1;
        for (std::size_t s = 0; s < stacks.size(); ++s)
        {
            SplitMix64 random{splitmix64(seed ^ (std::uint64_t(s + 1) * 0x9e3779b97f4a7c15ull) ^ std::uint64_t(set) << 56)};
            StackSums sums(bin_count);
            for (std::uint64_t path = 0; path < counts[s]; ++path)
            {
                const LayeredExit exit = layered_trace(stacks[s], view, random);
                estimate.capped += exit.capped ? 1 : 0;
                sums.add(exit, exit.left ? grid.bin_of(exit.direction) : -1, only_channel);
            }
            estimate.paths += counts[s];
            const double w = stacks[s].weight;
            double mean = 0.0;
            double variance = 0.0;
            for (std::size_t c = 0; c < 3; ++c)
            {
                mean_and_variance(sums.total[c], sums.total_squares[c], sums.paths, mean, variance);
                estimate.albedo[c] += w * mean;
                variance_total[c] += w * w * variance;
                mean_and_variance(sums.reflected[c], sums.reflected_squares[c], sums.paths, mean, variance);
                estimate.reflected[c] += w * mean;
                variance_reflected[c] += w * w * variance;
                mean_and_variance(sums.transmitted[c], sums.transmitted_squares[c], sums.paths, mean, variance);
                estimate.transmitted[c] += w * mean;
                variance_transmitted[c] += w * w * variance;
                for (int b = 0; b < bin_count; ++b)
                {
                    mean_and_variance(sums.bins[std::size_t(b)][c], sums.bin_squares[std::size_t(b)][c], sums.paths, mean,
                                      variance);
                    estimate.bins[std::size_t(b)][c] += w * mean * inverse_solid_angle;
                    bin_variances[std::size_t(b)][c] += w * w * variance * inverse_solid_angle * inverse_solid_angle;
                }
            }
            mean_and_variance(sums.luminance_sum, sums.luminance_squares, sums.paths, mean, variance);
            luminance_variance += w * w * variance;
        }
    }
    for (std::size_t c = 0; c < 3; ++c)
    {
        estimate.albedo_error[c] = std::sqrt(variance_total[c]);
        estimate.reflected_error[c] = std::sqrt(variance_reflected[c]);
        estimate.transmitted_error[c] = std::sqrt(variance_transmitted[c]);
        for (int b = 0; b < bin_count; ++b)
        {
            estimate.bin_errors[std::size_t(b)][c] = std::sqrt(bin_variances[std::size_t(b)][c]);
        }
    }
    // Per channel, each channel's luminance share came from its own paths: the sum of the three
    // sets' variances is that of the combined luminance.
    estimate.luminance_error = std::sqrt(luminance_variance);
    estimate.seconds = watch.seconds();
    estimate.cpu_seconds = cpu_watch.seconds();
    return estimate;
}

std::array<LayeredColor, 2> layered_bin_transfer(const LayeredMaterial& material, const LayeredGrid& grid, int from_bin,
                                                 int to_bin, std::uint64_t paths, std::uint64_t seed)
{
    const int per_hemisphere = grid.bins_per_hemisphere();
    if (from_bin < 0 || from_bin >= per_hemisphere || to_bin < 0 || to_bin >= per_hemisphere || paths == 0)
    {
        throw std::invalid_argument("layered_bin_transfer: reflection bins and paths > 0 only");
    }
    const double solid_angle = grid.bin_solid_angle();
    // Stratified over the bin's square: a sqrt(paths) x sqrt(paths) lattice, jittered.
    const std::uint64_t side = std::max<std::uint64_t>(1, std::uint64_t(std::sqrt(double(paths))));
    std::array<LayeredColor, 2> result{};
    const int channel_sets = material.per_channel ? 3 : 1;
    for (int set = 0; set < channel_sets; ++set)
    {
        const std::vector<LayeredStack>& stacks = material.stacks[std::size_t(set)];
        for (std::size_t s = 0; s < stacks.size(); ++s)
        {
            SplitMix64 random{splitmix64(seed ^ (std::uint64_t(s + 1) * 0x9e3779b97f4a7c15ull) ^ std::uint64_t(set) << 56)};
            LayeredColor sum{}, squares{};
            for (std::uint64_t path = 0; path < paths; ++path)
            {
                const double u = (double(path % side) + random.next_double()) / double(side);
                const double v = (double((path / side) % side) + random.next_double()) / double(side);
                const glm::dvec3 view = grid.bin_direction(from_bin, u, v);
                const LayeredExit exit = layered_trace(stacks[s], view, random);
                if (!exit.left || grid.bin_of(exit.direction) != to_bin)
                {
                    continue;
                }
                for (std::size_t c = 0; c < 3; ++c)
                {
                    const bool counted = !material.per_channel || int(c) == set;
                    const double value = counted ? exit.weight[c] * view.z * solid_angle : 0.0;
                    sum[c] += value;
                    squares[c] += value * value;
                }
            }
            const double w = stacks[s].weight;
            for (std::size_t c = 0; c < 3; ++c)
            {
                double mean = 0.0;
                double variance = 0.0;
                mean_and_variance(sum[c], squares[c], paths, mean, variance);
                result[0][c] += w * mean;
                result[1][c] += w * w * variance;
            }
        }
    }
    for (double& variance : result[1])
    {
        variance = std::sqrt(variance);
    }
    return result;
}

}  // namespace openpbr::host
