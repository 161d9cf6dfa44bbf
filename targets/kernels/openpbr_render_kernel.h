// The body of the preview path tracer, shared by every backend: the Slang compute kernel
// (render.slang) and the CPU renderer (host/preview/render.cpp) include this same text, so both run
// identical code (one pixel sample per call of openpbr_render_sample).
//
// Scene (one per gallery cell, in the cell's own coordinates): up to OPENPBR_RENDER_MAX_OBJECTS
// spheres, each with its own material (a plain gallery cell has one, of radius R centred at the
// origin), a ground plane y = -R (a neutral OpenPBR material with a checker on its base color),
// a gradient sky with a soft sun glow (or a uniform environment), and one spherical area light.
// Everything is analytic (ray-sphere, ray-plane).
//
// Nested media (Schmidt and Budge 2002, "Simple nested dielectrics in ray traced images",
// JGT 7(2)): every path carries the set of the cell's objects it is inside, one bit per object
// (the medium stack, ordered by priority instead of by entry). An object's priority is its
// index in the cell: later objects win where objects overlap, so a cell lists its objects from
// the outside in (a glass shell, then the water in it). The medium the path travels in is the
// entered object of highest priority, or the environment's (air, IOR 1) when the set is empty.
// At a hit on object k's surface:
//  - k's surface inside a medium of higher priority than k is not an interface (a false hit):
//    the path goes straight on and only k's membership changes;
//  - otherwise the surface is the interface between k's medium (IOR = k's specular_ior) and
//    the medium outside k: the entered object of highest priority other than k. k's material
//    is prepared with that medium's IOR as exterior_ior, so the BSDF sees the relative IOR of
//    the two media (water in glass from either side: 1.33 / 1.52 = 0.875; a bubble in water:
//    1 / 1.33), whichever side the path arrives from.
// Transmission across a non-thin-walled object's surface adds it to the set (entering, below
// its outward normal) or removes it (leaving); thin-walled objects never enter the set. Inside,
// the path is in that object's homogeneous volume (transmission_color/depth, subsurface), the
// one openpbr_prepare_volume gives, written by the host per object. The set holds one bit per
// object, so it cannot overflow: its depth cap is the object count of a cell, which the host
// checks (more objects are an error there). A path inside a medium that finds no surface ahead
// (rounding at a grazing exit) ends without light.
//
// Integrator: unidirectional path tracing. Next-event estimation towards one emitter per
// vertex, chosen uniformly among the area light and (from the ground) the cell's first object
// when its material emits, combined with BSDF sampling by multiple importance sampling (power
// heuristic, the emitter's pdf including its selection probability); BSDF sampling through
// openpbr_sample; Russian roulette after RR_DEPTH events (survival max(throughput) capped at
// 1); at most MAX_DEPTH surface events and MAX_VOLUME_EVENTS scattering events in a medium.
// A path that transmits into a non-thin-walled sphere is inside its medium until it transmits
// out: distances are sampled with openpbr_volume_sample_distance (spectral MIS over the
// channels) and directions with the Henyey-Greenstein phase function; there is no next-event
// estimation at medium scattering events (only at the interface, where a rough interface seen
// from inside transmits the light in; every object of the cell blocks shadow rays, so light
// reaches an inner interface by BSDF sampling only). Thin-walled spheres have no interior.
// Cells with a dispersive object (openpbr_needs_rgb_wavelengths) get one wavelength per RGB
// channel per path,
// uniform in the channel's box: B 400-500 nm, G 500-600 nm, R 600-700 nm (the pixel average
// integrates each channel over its box); others use the library's default wavelengths.
//
// Structure: a path is openpbr_render_path_setup (what it knows from its pixel and sample),
// openpbr_render_path_begin, openpbr_render_path_step until it is done (at most step_limit
// steps), then openpbr_render_path_end; openpbr_render_sample runs that loop, and a backend that
// cannot compile the loop (SwiftShader, the WebGPU viewer: render_steps.slang) runs one step per
// dispatch with the state in a buffer. Both give the same samples.
//
// Random numbers: a PCG hash (O'Neill 2014; the 32-bit RXS-M-XS output permutation) of
// (seed, pixel, sample, bounce, dimension), so any sample of any pixel is reproducible alone.
//
// Accumulation record per pixel (OPENPBR_RENDER_ACCUMULATION_FLOATS floats): sum of the
// radiance (3), sum of its square (3), number of non-finite samples (set to 0 and counted),
// number of samples whose camera ray hit the sphere.
//
// The includer defines OPENPBR_RENDER_PARAMETER(index) -> uint, OPENPBR_RENDER_SCENE(index)
// -> float, OPENPBR_RENDER_MATERIAL(index) -> float, OPENPBR_RENDER_ACCUMULATION_READ(index)
// -> float and OPENPBR_RENDER_ACCUMULATION_WRITE(index, value), and has the OpenPBR API in
// scope. Its packed-material reader is openpbr_render_unpack_material, the reader of
// slang/openpbr_material_packing.h under its own name (the conformance kernel's
// openpbr_unpack_material reads another buffer in the same C++ program).
#ifndef OPENPBR_RENDER_KERNEL_H
#define OPENPBR_RENDER_KERNEL_H

#define OPENPBR_MATERIAL_UNPACK_NAME openpbr_render_unpack_material
#define OPENPBR_MATERIAL_UNPACK_READ(index) OPENPBR_RENDER_MATERIAL(index)
#include "../../slang/openpbr_material_packing.h"

// ---- Parameter buffer (uint) ----
#define OPENPBR_RENDER_PARAMETER_WIDTH 0
#define OPENPBR_RENDER_PARAMETER_HEIGHT 1
#define OPENPBR_RENDER_PARAMETER_SAMPLE_BEGIN 2
#define OPENPBR_RENDER_PARAMETER_SAMPLE_END 3
#define OPENPBR_RENDER_PARAMETER_SEED 4
#define OPENPBR_RENDER_PARAMETER_CELL_SIZE 5
#define OPENPBR_RENDER_PARAMETER_COLUMNS 6
#define OPENPBR_RENDER_PARAMETER_CELL_COUNT 7       // cells with a sphere (= materials shown)
#define OPENPBR_RENDER_PARAMETER_GROUND_MATERIAL 8  // index of the ground's packed material
#define OPENPBR_RENDER_PARAMETER_FLAGS 9
#define OPENPBR_RENDER_PARAMETER_MAX_DEPTH 10
#define OPENPBR_RENDER_PARAMETER_MAX_VOLUME_EVENTS 11
#define OPENPBR_RENDER_PARAMETER_RR_DEPTH 12
#define OPENPBR_RENDER_PARAMETER_COUNT 16

#define OPENPBR_RENDER_FLAG_GROUND 1u
#define OPENPBR_RENDER_FLAG_LIGHT 2u
#define OPENPBR_RENDER_FLAG_SKY 4u  // gradient sky; otherwise the uniform environment

// ---- Scene buffer (float) ----
#define OPENPBR_RENDER_SCENE_CAMERA_POSITION 0  // 3
#define OPENPBR_RENDER_SCENE_CAMERA_FORWARD 3   // 3, unit
#define OPENPBR_RENDER_SCENE_CAMERA_RIGHT 6     // 3, scaled by tan(fov / 2)
#define OPENPBR_RENDER_SCENE_CAMERA_UP 9        // 3, scaled by tan(fov / 2)
#define OPENPBR_RENDER_SCENE_SPHERE_RADIUS 12
#define OPENPBR_RENDER_SCENE_LIGHT_CENTER 13  // 3
#define OPENPBR_RENDER_SCENE_LIGHT_RADIUS 16
#define OPENPBR_RENDER_SCENE_LIGHT_RADIANCE 17  // 3, render units
#define OPENPBR_RENDER_SCENE_SKY_ZENITH 20      // 3
#define OPENPBR_RENDER_SCENE_SKY_HORIZON 23     // 3
#define OPENPBR_RENDER_SCENE_ENVIRONMENT 26     // 3: uniform environment, or the sky below the horizon
#define OPENPBR_RENDER_SCENE_SUN_DIRECTION 29   // 3, unit
#define OPENPBR_RENDER_SCENE_SUN_GLOW 32        // 3
#define OPENPBR_RENDER_SCENE_SUN_EXPONENT 35
#define OPENPBR_RENDER_SCENE_NITS_TO_UNITS 36  // render units per nit (emission)
#define OPENPBR_RENDER_SCENE_CHECKER_SIZE 37
#define OPENPBR_RENDER_SCENE_CHECKER_DARK 38         // base_color factor of the dark squares
#define OPENPBR_RENDER_SCENE_DEFAULT_WAVELENGTHS 39  // 3: OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM
#define OPENPBR_RENDER_SCENE_COUNT 44                // the header; the object records follow it

// ---- Object records (float), after the header: OPENPBR_RENDER_MAX_OBJECTS per cell ----
// Record of object `slot` of cell `cell`: OPENPBR_RENDER_SCENE_COUNT + (cell *
// OPENPBR_RENDER_MAX_OBJECTS + slot) * OPENPBR_RENDER_OBJECT_FLOATS. A cell's objects fill its
// first slots; radius 0 marks the unused ones.
#define OPENPBR_RENDER_MAX_OBJECTS 4u
#define OPENPBR_RENDER_OBJECT_FLOATS 16u
#define OPENPBR_RENDER_OBJECT_CENTER 0u      // 3
#define OPENPBR_RENDER_OBJECT_RADIUS 3u      // > 0 for an object, 0 for an unused slot
#define OPENPBR_RENDER_OBJECT_MATERIAL 4u    // index of its packed material (an integer)
#define OPENPBR_RENDER_OBJECT_MEDIUM_IOR 5u  // IOR of its interior medium: its specular_ior
#define OPENPBR_RENDER_OBJECT_ENCLOSES 6u    // 1: a path can be inside it (not thin-walled); 0
#define OPENPBR_RENDER_OBJECT_DISPERSIVE 7u  // 1: openpbr_needs_rgb_wavelengths of its material
#define OPENPBR_RENDER_OBJECT_EXTINCTION 8u  // 3: its volume (openpbr_prepare_volume)
#define OPENPBR_RENDER_OBJECT_ALBEDO 11u     // 3
#define OPENPBR_RENDER_OBJECT_ANISOTROPY 14u
#define OPENPBR_RENDER_OBJECT_VOLUME_PRESENT 15u  // 1 or 0

#define OPENPBR_RENDER_ACCUMULATION_FLOATS 8

// The library's macros do not cross the Slang module boundary, so the kernel spells the few it
// needs itself (host/preview/render.cpp checks them against the library's with static_assert).
#define OPENPBR_RENDER_FLOAT_MAX 3.4e+38f  // = OPENPBR_FLOAT_MAX (Slang reads 3.40282347e+38f as inf)
#define OPENPBR_RENDER_TWO_PI 6.28318530717958647692f
#define OPENPBR_RENDER_LOBE_TYPE_SPECULAR 16u

// Hit kinds.
#define OPENPBR_RENDER_HIT_NONE 0u
#define OPENPBR_RENDER_HIT_OBJECT 1u  // one of the cell's spheres
#define OPENPBR_RENDER_HIT_GROUND 2u
#define OPENPBR_RENDER_HIT_LIGHT 3u

// Random-number dimensions per bounce.
#define OPENPBR_RENDER_DIMENSION_LIGHT_U 0u
#define OPENPBR_RENDER_DIMENSION_LIGHT_V 1u
#define OPENPBR_RENDER_DIMENSION_EMITTER_U 2u  // which emitter
#define OPENPBR_RENDER_DIMENSION_BSDF 4u       // 3 numbers
#define OPENPBR_RENDER_DIMENSION_ROULETTE 7u
#define OPENPBR_RENDER_DIMENSION_VOLUME 8u   // 4 numbers: channel, distance, phase (2)
#define OPENPBR_RENDER_DIMENSION_CAMERA 12u  // bounce 0 only: 2 jitter, 3 wavelengths
#define OPENPBR_RENDER_DIMENSIONS_PER_BOUNCE 16u

OPENPBR_NAMESPACE_BEGIN

struct OpenPBR_RenderSample
{
    vec3 radiance;    // 0 when the sample was non-finite
    bool hit_object;  // the camera ray hit the sphere
    bool nonfinite;   // a non-finite value was met (and replaced by 0)
};

struct OpenPBR_RenderCone
{
    vec3 direction;
    float pdf;       // solid angle
    float distance;  // to the sphere's surface
    bool valid;
};

// ---- Random numbers ----

OPENPBR_FUNC uint openpbr_render_hash(uint value)
{
    const uint state = value * 747796405u + 2891336453u;
    const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

OPENPBR_FUNC uint openpbr_render_path_key(uint seed, uint pixel, uint sample_index)
{
    return openpbr_render_hash(seed ^ openpbr_render_hash(pixel ^ openpbr_render_hash(sample_index + 0x9e3779b9u)));
}

// Uniform in [0, 1 - 2^-24]: 24 bits, exactly representable, never 1.
OPENPBR_FUNC float openpbr_render_random(uint path_key, uint bounce, uint dimension)
{
    const uint bits =
        openpbr_render_hash(path_key ^ openpbr_render_hash(bounce * OPENPBR_RENDER_DIMENSIONS_PER_BOUNCE + dimension));
    return float(bits >> 8u) * (1.0f / 16777216.0f);
}

// ---- Buffers ----

OPENPBR_FUNC vec3 openpbr_render_scene_vec3(uint index)
{
    return vec3(OPENPBR_RENDER_SCENE(index), OPENPBR_RENDER_SCENE(index + 1u), OPENPBR_RENDER_SCENE(index + 2u));
}

// ---- Geometry ----

// Nearest hit of the ray with a sphere beyond t_min, or -1. The discriminant is formed from the
// distance of the centre to the ray (Haines et al., "Precision improvements for ray/sphere
// intersection", Ray Tracing Gems 2019), which keeps it accurate for distant spheres.
OPENPBR_FUNC float openpbr_render_intersect_sphere(vec3 origin, vec3 direction, vec3 center, float radius, float t_min)
{
    const vec3 offset = origin - center;
    const float b = dot(offset, direction);
    const vec3 closest = offset - direction * b;
    const float discriminant = radius * radius - dot(closest, closest);
    if (!(discriminant >= 0.0f))
    {
        return -1.0f;
    }
    const float root = sqrt(discriminant);
    // The near root from the numerically stable pair (q = -b - sign(b) root).
    const float q = b >= 0.0f ? -b - root : -b + root;
    const float c = dot(offset, offset) - radius * radius;
    const float t0 = b >= 0.0f ? c / q : q;
    const float t1 = b >= 0.0f ? q : c / q;
    const float near_t = min(t0, t1);
    const float far_t = max(t0, t1);
    if (near_t > t_min)
    {
        return near_t;
    }
    if (far_t > t_min)
    {
        return far_t;
    }
    return -1.0f;
}

OPENPBR_FUNC float openpbr_render_intersect_ground(vec3 origin, vec3 direction, float ground_y, float t_min)
{
    if (direction.y == 0.0f)
    {
        return -1.0f;
    }
    const float t = (ground_y - origin.y) / direction.y;
    return t > t_min ? t : -1.0f;
}

// Uniform sampling of the cone of directions a sphere subtends (the solid angle it covers).
OPENPBR_FUNC OpenPBR_RenderCone openpbr_render_sample_cone(vec3 position, vec3 center, float radius, vec2 u)
{
    OpenPBR_RenderCone cone;
    cone.direction = vec3(0.0f, 0.0f, 1.0f);
    cone.pdf = 0.0f;
    cone.distance = 0.0f;
    cone.valid = false;
    const vec3 to_center = center - position;
    const float distance_squared = dot(to_center, to_center);
    const float radius_squared = radius * radius;
    if (!(distance_squared > radius_squared * 1.0001f))
    {
        return cone;
    }
    const float sin_squared_max = radius_squared / distance_squared;
    const float cos_max = sqrt(max(1.0f - sin_squared_max, 0.0f));
    const float one_minus_cos_max = sin_squared_max / (1.0f + cos_max);  // 1 - cos_max without cancellation
    const float one_minus_cos = u.x * one_minus_cos_max;
    const float cos_theta = 1.0f - one_minus_cos;
    const float sin_theta = sqrt(max(one_minus_cos * (2.0f - one_minus_cos), 0.0f));
    const float phi = OPENPBR_RENDER_TWO_PI * u.y;
    const float distance_to_center = sqrt(distance_squared);
    const OpenPBR_Basis frame = openpbr_make_basis(to_center / distance_to_center);
    cone.direction = openpbr_to_world(frame, vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta));
    cone.pdf = 1.0f / (OPENPBR_RENDER_TWO_PI * one_minus_cos_max);
    // Distance to the near side along the sampled direction (the direction lies in the cone).
    const float across = distance_squared * sin_theta * sin_theta;
    cone.distance = max(distance_to_center * cos_theta - sqrt(max(radius_squared - across, 0.0f)), 0.0f);
    cone.valid = cone.pdf > 0.0f && cone.pdf <= OPENPBR_RENDER_FLOAT_MAX;
    return cone;
}

OPENPBR_FUNC float openpbr_render_cone_pdf(vec3 position, vec3 center, float radius)
{
    const vec3 to_center = center - position;
    const float distance_squared = dot(to_center, to_center);
    const float radius_squared = radius * radius;
    if (!(distance_squared > radius_squared * 1.0001f))
    {
        return 0.0f;
    }
    const float sin_squared_max = radius_squared / distance_squared;
    const float cos_max = sqrt(max(1.0f - sin_squared_max, 0.0f));
    return 1.0f / (OPENPBR_RENDER_TWO_PI * (sin_squared_max / (1.0f + cos_max)));
}

// Power heuristic (Veach 1997, beta = 2) for the technique with density `a` against `b`.
OPENPBR_FUNC float openpbr_render_power_heuristic(float a, float b)
{
    const float a2 = a * a;
    const float b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

OPENPBR_FUNC bool openpbr_render_is_finite(vec3 v)
{
    return v.x >= -OPENPBR_RENDER_FLOAT_MAX && v.x <= OPENPBR_RENDER_FLOAT_MAX && v.y >= -OPENPBR_RENDER_FLOAT_MAX &&
           v.y <= OPENPBR_RENDER_FLOAT_MAX && v.z >= -OPENPBR_RENDER_FLOAT_MAX && v.z <= OPENPBR_RENDER_FLOAT_MAX;
}

// Radiance of the environment seen along a direction (render units).
OPENPBR_FUNC vec3 openpbr_render_environment(vec3 direction, uint flags)
{
    const vec3 environment = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_ENVIRONMENT);
    if ((flags & OPENPBR_RENDER_FLAG_SKY) == 0u)
    {
        return environment;
    }
    const vec3 zenith = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_SKY_ZENITH);
    const vec3 horizon = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_SKY_HORIZON);
    const vec3 sky = direction.y >= 0.0f ? mix(horizon, zenith, sqrt(direction.y)) : environment;
    const float sun = max(dot(direction, openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_SUN_DIRECTION)), 0.0f);
    return sky + openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_SUN_GLOW) *
                     pow(sun, OPENPBR_RENDER_SCENE(OPENPBR_RENDER_SCENE_SUN_EXPONENT));
}

// ---- Objects of a cell ----

struct OpenPBR_RenderObjectHit
{
    float t;    // distance along the ray, or -1
    uint slot;  // the object hit, or OPENPBR_RENDER_MAX_OBJECTS
};

OPENPBR_FUNC uint openpbr_render_object_record(uint cell, uint slot)
{
    return uint(OPENPBR_RENDER_SCENE_COUNT) + (cell * OPENPBR_RENDER_MAX_OBJECTS + slot) * OPENPBR_RENDER_OBJECT_FLOATS;
}

OPENPBR_FUNC float openpbr_render_object_float(uint cell, uint slot, uint field)
{
    return OPENPBR_RENDER_SCENE(openpbr_render_object_record(cell, slot) + field);
}

OPENPBR_FUNC vec3 openpbr_render_object_center(uint cell, uint slot)
{
    return openpbr_render_scene_vec3(openpbr_render_object_record(cell, slot) + OPENPBR_RENDER_OBJECT_CENTER);
}

// The cell's objects fill its first slots; an unused slot has radius 0.
OPENPBR_FUNC uint openpbr_render_object_count(uint cell)
{
    uint count = 0u;
    for (uint slot = 0u; slot < OPENPBR_RENDER_MAX_OBJECTS; ++slot)
    {
        if (count == slot && openpbr_render_object_float(cell, slot, OPENPBR_RENDER_OBJECT_RADIUS) > 0.0f)
        {
            count = slot + 1u;
        }
    }
    return count;
}

// Nearest hit beyond 0 among the cell's first `count` objects (ties: the earlier object).
OPENPBR_FUNC OpenPBR_RenderObjectHit openpbr_render_intersect_objects(vec3 origin, vec3 direction, uint cell, uint count)
{
    OpenPBR_RenderObjectHit hit;
    hit.t = -1.0f;
    hit.slot = OPENPBR_RENDER_MAX_OBJECTS;
    for (uint slot = 0u; slot < count; ++slot)
    {
        const float t =
            openpbr_render_intersect_sphere(origin, direction, openpbr_render_object_center(cell, slot),
                                            openpbr_render_object_float(cell, slot, OPENPBR_RENDER_OBJECT_RADIUS), 0.0f);
        if (t > 0.0f && (hit.slot == OPENPBR_RENDER_MAX_OBJECTS || t < hit.t))
        {
            hit.t = t;
            hit.slot = slot;
        }
    }
    return hit;
}

// The medium of a set of entered objects: the one of highest priority (the highest set bit),
// or OPENPBR_RENDER_MAX_OBJECTS for the empty set (the environment).
OPENPBR_FUNC uint openpbr_render_top_object(uint inside_set)
{
    uint top = OPENPBR_RENDER_MAX_OBJECTS;
    for (uint slot = 0u; slot < OPENPBR_RENDER_MAX_OBJECTS; ++slot)
    {
        if (((inside_set >> slot) & 1u) != 0u)
        {
            top = slot;
        }
    }
    return top;
}

// IOR of the medium inside `slot`; the environment (no object) is air, IOR 1.
OPENPBR_FUNC float openpbr_render_medium_ior(uint cell, uint slot)
{
    return slot < OPENPBR_RENDER_MAX_OBJECTS ? openpbr_render_object_float(cell, slot, OPENPBR_RENDER_OBJECT_MEDIUM_IOR)
                                             : 1.0f;
}

// The homogeneous volume inside `slot` (empty for the environment).
OPENPBR_FUNC OpenPBR_HomogeneousVolume openpbr_render_medium_volume(uint cell, uint slot)
{
    OpenPBR_HomogeneousVolume volume = openpbr_make_empty_volume();
    if (slot < OPENPBR_RENDER_MAX_OBJECTS)
    {
        const uint record = openpbr_render_object_record(cell, slot);
        volume.extinction = openpbr_render_scene_vec3(record + OPENPBR_RENDER_OBJECT_EXTINCTION);
        volume.albedo = openpbr_render_scene_vec3(record + OPENPBR_RENDER_OBJECT_ALBEDO);
        volume.anisotropy = OPENPBR_RENDER_SCENE(record + OPENPBR_RENDER_OBJECT_ANISOTROPY);
        volume.is_present = OPENPBR_RENDER_SCENE(record + OPENPBR_RENDER_OBJECT_VOLUME_PRESENT) != 0.0f;
    }
    return volume;
}

// Whether anything (the cell's first `object_count` objects, the ground) blocks the segment
// from origin to distance.
OPENPBR_FUNC bool openpbr_render_occluded(vec3 origin, vec3 direction, float distance_value, uint cell, uint object_count,
                                          float radius, uint flags)
{
    const float limit = distance_value * 0.9999f;
    const OpenPBR_RenderObjectHit hit = openpbr_render_intersect_objects(origin, direction, cell, object_count);
    if (hit.t > 0.0f && hit.t < limit)
    {
        return true;
    }
    if ((flags & OPENPBR_RENDER_FLAG_GROUND) != 0u)
    {
        const float t = openpbr_render_intersect_ground(origin, direction, -radius, 0.0f);
        if (t > 0.0f && t < limit)
        {
            return true;
        }
    }
    return false;
}

// ---- One path ----

// Emitters for next-event estimation: the area light and, seen from the ground, the cell's
// first object when its material emits (an emitting object inside another is reached by BSDF
// sampling only). One is chosen uniformly per vertex (one call site of eval
// and pdf keeps the kernel small: lavapipe's pipeline creation time grows with it).
#define OPENPBR_RENDER_EMITTER_LIGHT 1u
#define OPENPBR_RENDER_EMITTER_SPHERE 2u

OPENPBR_FUNC float openpbr_render_emitter_selection(uint candidates)
{
    const uint count = (candidates & 1u) + ((candidates >> 1u) & 1u);
    return count > 0u ? 1.0f / float(count) : 0.0f;
}

// What one path of one pixel sample knows before it starts and never changes: the settings,
// the scene values it reads, the cell's first object and the wavelengths. A pure function of
// (pixel, sample), so a backend that runs a path one step per dispatch (the WebGPU viewer,
// render_steps.slang) recomputes it at every step instead of storing it.
struct OpenPBR_RenderPath
{
    uint flags;
    uint max_depth;
    uint max_volume_events;
    uint roulette_depth;
    uint step_limit;  // events of every kind a path may take: max_depth + max_volume_events + 2
    uint cell_index;
    uint ground_material;
    uint key;
    uint object_count;
    bool has_ground;
    bool has_light;
    bool sphere_emissive;
    float radius;
    float ground_y;
    float epsilon;
    vec3 light_center;
    float light_radius;
    vec3 light_radiance;
    float nits_to_units;
    float checker_size;
    float checker_dark;
    OpenPBR_ResolvedInputs sphere_inputs;
    vec3 sphere_center;
    float sphere_radius;
    vec3 wavelengths;
    vec3 ground_wavelengths;
    vec3 camera_origin;
    vec3 camera_direction;
};

// What a path carries from one step (a surface, a medium event, or the escape) to the next.
// The medium it is in is not stored: it is always that of the top object of inside_set
// (openpbr_render_path_step recomputes it).
struct OpenPBR_RenderPathState
{
    vec3 throughput;
    vec3 radiance;
    vec3 origin;
    vec3 direction;
    // MIS state of the previous vertex: the emitters its next-event estimation could choose
    // (0 after a delta lobe or a medium event), its BSDF pdf for the sampled direction, its
    // position.
    vec3 previous_position;
    float previous_pdf;
    uint previous_candidates;
    // The medium stack: one bit per object of the cell the path is inside (see the top of this
    // file); the medium the path is in is the highest set bit's.
    uint inside_set;
    uint surface_events;
    uint volume_events;
    uint step;
    bool nonfinite;
    bool hit_object;  // the camera ray hit the sphere (set at step 0)
    bool done;
};

OPENPBR_FUNC OpenPBR_RenderPath openpbr_render_path_setup(uint pixel_x, uint pixel_y, uint sample_index)
{
    OpenPBR_RenderPath path;
    const uint width = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_WIDTH);
    const uint cell_size = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_CELL_SIZE);
    const uint columns = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_COLUMNS);
    path.flags = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_FLAGS);
    path.max_depth = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_MAX_DEPTH);
    path.max_volume_events = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_MAX_VOLUME_EVENTS);
    path.roulette_depth = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_RR_DEPTH);
    path.step_limit = path.max_depth + path.max_volume_events + 2u;
    path.cell_index = (pixel_y / cell_size) * columns + pixel_x / cell_size;
    const bool has_sphere = path.cell_index < OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_CELL_COUNT);
    path.ground_material = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_GROUND_MATERIAL);
    path.has_ground = (path.flags & OPENPBR_RENDER_FLAG_GROUND) != 0u;
    path.has_light = (path.flags & OPENPBR_RENDER_FLAG_LIGHT) != 0u;

    path.key = openpbr_render_path_key(OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_SEED), pixel_y * width + pixel_x,
                                       sample_index);

    path.radius = OPENPBR_RENDER_SCENE(OPENPBR_RENDER_SCENE_SPHERE_RADIUS);
    path.ground_y = -path.radius;
    path.epsilon = 2e-4f * max(path.radius, 1e-3f);
    path.light_center = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_LIGHT_CENTER);
    path.light_radius = OPENPBR_RENDER_SCENE(OPENPBR_RENDER_SCENE_LIGHT_RADIUS);
    path.light_radiance = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_LIGHT_RADIANCE);
    path.nits_to_units = OPENPBR_RENDER_SCENE(OPENPBR_RENDER_SCENE_NITS_TO_UNITS);
    path.checker_size = OPENPBR_RENDER_SCENE(OPENPBR_RENDER_SCENE_CHECKER_SIZE);
    path.checker_dark = OPENPBR_RENDER_SCENE(OPENPBR_RENDER_SCENE_CHECKER_DARK);

    // Camera ray through a jittered point of the pixel, in the cell's [-1, 1]^2 image plane.
    const float local_x = float(pixel_x % cell_size) + openpbr_render_random(path.key, 0u, OPENPBR_RENDER_DIMENSION_CAMERA);
    const float local_y =
        float(pixel_y % cell_size) + openpbr_render_random(path.key, 0u, OPENPBR_RENDER_DIMENSION_CAMERA + 1u);
    const float ndc_x = 2.0f * local_x / float(cell_size) - 1.0f;
    const float ndc_y = 1.0f - 2.0f * local_y / float(cell_size);
    path.camera_origin = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_CAMERA_POSITION);
    path.camera_direction = normalize(openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_CAMERA_FORWARD) +
                                      openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_CAMERA_RIGHT) * ndc_x +
                                      openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_CAMERA_UP) * ndc_y);

    // The cell's first object is the emitter next-event estimation can aim at.
    path.object_count = has_sphere ? openpbr_render_object_count(path.cell_index) : 0u;
    path.sphere_inputs = openpbr_make_default_resolved_inputs();
    path.sphere_center = vec3(0.0f);
    path.sphere_radius = path.radius;
    bool dispersive = false;
    if (path.object_count > 0u)
    {
        path.sphere_inputs = openpbr_render_unpack_material(
            uint(openpbr_render_object_float(path.cell_index, 0u, OPENPBR_RENDER_OBJECT_MATERIAL)));
        path.sphere_center = openpbr_render_object_center(path.cell_index, 0u);
        path.sphere_radius = openpbr_render_object_float(path.cell_index, 0u, OPENPBR_RENDER_OBJECT_RADIUS);
        for (uint slot = 0u; slot < path.object_count; ++slot)
        {
            dispersive =
                dispersive || openpbr_render_object_float(path.cell_index, slot, OPENPBR_RENDER_OBJECT_DISPERSIVE) != 0.0f;
        }
    }
    path.sphere_emissive = path.object_count > 0u && path.sphere_inputs.emission_luminance > 0.0f &&
                           openpbr_max3(path.sphere_inputs.emission_color) > 0.0f;

    // Wavelengths: one per channel, uniform in the channel's box, when an object of the cell is
    // dispersive; otherwise the library's default (the host writes OPENPBR_DEFAULT_RGB_WAVELENGTHS_NM).
    path.wavelengths = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_DEFAULT_WAVELENGTHS);
    if (dispersive)
    {
        path.wavelengths = vec3(600.0f + 100.0f * openpbr_render_random(path.key, 0u, OPENPBR_RENDER_DIMENSION_CAMERA + 2u),
                                500.0f + 100.0f * openpbr_render_random(path.key, 0u, OPENPBR_RENDER_DIMENSION_CAMERA + 3u),
                                400.0f + 100.0f * openpbr_render_random(path.key, 0u, OPENPBR_RENDER_DIMENSION_CAMERA + 4u));
    }
    path.ground_wavelengths = openpbr_render_scene_vec3(OPENPBR_RENDER_SCENE_DEFAULT_WAVELENGTHS);
    return path;
}

OPENPBR_FUNC OpenPBR_RenderPathState openpbr_render_path_begin(OPENPBR_IN(OpenPBR_RenderPath) path)
{
    OpenPBR_RenderPathState state;
    state.throughput = vec3(1.0f);
    state.radiance = vec3(0.0f);
    state.origin = path.camera_origin;
    state.direction = path.camera_direction;
    state.previous_position = path.camera_origin;
    state.previous_pdf = 0.0f;
    state.previous_candidates = 0u;
    state.inside_set = 0u;
    state.surface_events = 0u;
    state.volume_events = 0u;
    state.step = 0u;
    state.nonfinite = false;
    state.hit_object = false;
    state.done = false;
    return state;
}

// What a ray of a step meets first.
struct OpenPBR_RenderHit
{
    uint kind;  // OPENPBR_RENDER_HIT_*
    float t;    // distance along the ray; OPENPBR_RENDER_FLOAT_MAX for none
    uint slot;  // the object hit (kind OPENPBR_RENDER_HIT_OBJECT), else OPENPBR_RENDER_MAX_OBJECTS
};

// Closest hit among the objects, the ground and the light (the last two only from outside
// every object).
OPENPBR_FUNC OpenPBR_RenderHit openpbr_render_closest_hit(OPENPBR_IN(OpenPBR_RenderPath) path,
                                                          OPENPBR_IN(OpenPBR_RenderPathState) state)
{
    const bool in_medium = state.inside_set != 0u;
    const OpenPBR_RenderObjectHit object_hit =
        openpbr_render_intersect_objects(state.origin, state.direction, path.cell_index, path.object_count);
    OpenPBR_RenderHit hit;
    hit.kind = OPENPBR_RENDER_HIT_NONE;
    hit.t = OPENPBR_RENDER_FLOAT_MAX;
    hit.slot = object_hit.slot;
    if (object_hit.slot < OPENPBR_RENDER_MAX_OBJECTS)
    {
        hit.kind = OPENPBR_RENDER_HIT_OBJECT;
        hit.t = object_hit.t;
    }
    if (path.has_ground && !in_medium)
    {
        const float t = openpbr_render_intersect_ground(state.origin, state.direction, path.ground_y, 0.0f);
        if (t > 0.0f && t < hit.t)
        {
            hit.kind = OPENPBR_RENDER_HIT_GROUND;
            hit.t = t;
        }
    }
    if (path.has_light && !in_medium)
    {
        const float t =
            openpbr_render_intersect_sphere(state.origin, state.direction, path.light_center, path.light_radius, 0.0f);
        if (t > 0.0f && t < hit.t)
        {
            hit.kind = OPENPBR_RENDER_HIT_LIGHT;
            hit.t = t;
        }
    }
    return hit;
}

// Russian roulette: the path survives with probability max(throughput) capped at 1, its
// throughput divided by that; otherwise it ends.
OPENPBR_FUNC void openpbr_render_roulette(uint path_key, OPENPBR_INOUT(OpenPBR_RenderPathState) state, uint step)
{
    const float survival = min(openpbr_max3(state.throughput), 1.0f);
    if (!(openpbr_render_random(path_key, step, OPENPBR_RENDER_DIMENSION_ROULETTE) < survival))
    {
        state.done = true;
        return;
    }
    state.throughput = state.throughput / survival;
}

// Free flight in the medium the path is in, towards the surface at t_hit: the flight's weight,
// then either a scattering event before the surface (a new direction from the Henyey-Greenstein
// phase function, roulette after RR_DEPTH events; returns true: the step is over) or the
// surface reached (returns false: the step goes on there).
OPENPBR_FUNC bool openpbr_render_medium_flight(OPENPBR_IN(OpenPBR_RenderPath) path,
                                               OPENPBR_INOUT(OpenPBR_RenderPathState) state,
                                               OPENPBR_IN(OpenPBR_HomogeneousVolume) medium, float t_hit, uint step)
{
    const OpenPBR_VolumeDistanceSample flight = openpbr_volume_sample_distance(
        medium, state.throughput, t_hit, openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_VOLUME),
        openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_VOLUME + 1u));
    state.throughput = state.throughput * flight.weight;
    if (!flight.scattered)
    {
        return false;
    }
    state.volume_events += 1u;
    if (state.volume_events > path.max_volume_events)
    {
        state.done = true;
        return true;
    }
    state.origin = state.origin + state.direction * flight.distance;
    const float cos_theta = openpbr_henyey_greenstein_sample_cos_theta(
        medium.anisotropy, openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_VOLUME + 2u));
    const float sin_theta = sqrt(max(1.0f - cos_theta * cos_theta, 0.0f));
    const float phi = OPENPBR_RENDER_TWO_PI * openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_VOLUME + 3u);
    const OpenPBR_Basis frame = openpbr_make_basis(state.direction);
    state.direction = normalize(openpbr_to_world(frame, vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta)));
    state.previous_candidates = 0u;
    if (!openpbr_render_is_finite(state.throughput))
    {
        state.nonfinite = true;
        state.done = true;
        return true;
    }
    if (state.volume_events >= path.roulette_depth)
    {
        openpbr_render_roulette(path.key, state, step);
    }
    return true;
}

// Emission of the object hit: the cell's first object, a next-event target, weighted by MIS
// against the previous vertex's next-event estimation; an inner object in full.
OPENPBR_FUNC void openpbr_render_add_emission(OPENPBR_IN(OpenPBR_RenderPath) path,
                                              OPENPBR_INOUT(OpenPBR_RenderPathState) state, vec3 emission, uint slot,
                                              float previous_selection)
{
    if (slot == 0u && path.sphere_emissive)
    {
        const float weight = (state.previous_candidates & OPENPBR_RENDER_EMITTER_SPHERE) != 0u
                                 ? openpbr_render_power_heuristic(
                                       state.previous_pdf,
                                       previous_selection * openpbr_render_cone_pdf(state.previous_position,
                                                                                    path.sphere_center, path.sphere_radius))
                                 : 1.0f;
        state.radiance = state.radiance + state.throughput * emission * (path.nits_to_units * weight);
    }
    else if (slot != 0u)
    {
        // Inner objects are not next-event targets: their emission counts in full.
        state.radiance = state.radiance + state.throughput * emission * path.nits_to_units;
    }
}

// Next-event estimation towards one of the candidate emitters (also from the interface seen
// from inside: rough interfaces then transmit the light in; delta lobes give eval = 0). Every
// object of the cell occludes, except the emitting object when it is the target.
OPENPBR_FUNC void openpbr_render_next_event(OPENPBR_IN(OpenPBR_RenderPath) path,
                                            OPENPBR_INOUT(OpenPBR_RenderPathState) state,
                                            OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 position, vec3 normal,
                                            uint candidates, uint step)
{
    const float selection = openpbr_render_emitter_selection(candidates);
    const float u_emitter = openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_EMITTER_U);
    const bool pick_sphere =
        candidates == OPENPBR_RENDER_EMITTER_SPHERE ||
        (candidates == (OPENPBR_RENDER_EMITTER_LIGHT | OPENPBR_RENDER_EMITTER_SPHERE) && u_emitter < 0.5f);
    const vec3 emitter_center = pick_sphere ? path.sphere_center : path.light_center;
    const float emitter_radius = pick_sphere ? path.sphere_radius : path.light_radius;
    const OpenPBR_RenderCone cone =
        openpbr_render_sample_cone(position, emitter_center, emitter_radius,
                                   vec2(openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_LIGHT_U),
                                        openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_LIGHT_V)));
    if (!cone.valid)
    {
        return;
    }
    const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, cone.direction);
    const vec3 f = value.diffuse + value.specular;
    if (!(openpbr_max3(f) > 0.0f))
    {
        return;
    }
    vec3 emitted = path.light_radiance;
    if (pick_sphere)
    {
        OpenPBR_ResolvedInputs emitter_inputs = path.sphere_inputs;
        emitter_inputs.geometry_basis =
            openpbr_make_basis(normalize(position + cone.direction * cone.distance - path.sphere_center));
        emitter_inputs.geometry_coat_basis = emitter_inputs.geometry_basis;
        emitted = openpbr_prepare_emission(emitter_inputs, -cone.direction) * path.nits_to_units;
    }
    const float facing = dot(cone.direction, normal) >= 0.0f ? 1.0f : -1.0f;
    const vec3 shadow_origin = position + normal * (facing * path.epsilon);
    if (!openpbr_render_occluded(shadow_origin, cone.direction, cone.distance, path.cell_index,
                                 pick_sphere ? 0u : path.object_count, path.radius, path.flags))
    {
        const float light_pdf = selection * cone.pdf;
        const float weight = openpbr_render_power_heuristic(light_pdf, openpbr_pdf(bsdf, cone.direction));
        state.radiance = state.radiance + state.throughput * f * emitted * (weight / light_pdf);
    }
}

// The path goes on by sampling the BSDF: the new direction, the medium stack across the
// surface, the MIS state of this vertex, then roulette after RR_DEPTH surface events.
OPENPBR_FUNC void openpbr_render_continue_path(OPENPBR_IN(OpenPBR_RenderPath) path,
                                               OPENPBR_INOUT(OpenPBR_RenderPathState) state,
                                               OPENPBR_IN(OpenPBR_PreparedBsdf) bsdf, vec3 position, vec3 normal,
                                               bool encloses, uint slot_bit, uint candidates, uint step)
{
    const OpenPBR_BsdfSample bsdf_sample =
        openpbr_sample(bsdf, vec3(openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_BSDF),
                                  openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_BSDF + 1u),
                                  openpbr_render_random(path.key, step, OPENPBR_RENDER_DIMENSION_BSDF + 2u)));
    if (!(bsdf_sample.pdf > 0.0f))
    {
        state.done = true;
        return;
    }
    state.throughput = state.throughput * (bsdf_sample.weight.diffuse + bsdf_sample.weight.specular);
    if (!openpbr_render_is_finite(state.throughput))
    {
        state.nonfinite = true;
        state.done = true;
        return;
    }
    const bool delta = (bsdf_sample.lobe_type & OPENPBR_RENDER_LOBE_TYPE_SPECULAR) != 0u;
    state.previous_candidates = delta ? 0u : candidates;
    state.previous_pdf = bsdf_sample.pdf;
    state.previous_position = position;
    const float going = dot(bsdf_sample.direction, normal);
    if (encloses)
    {
        // Below the outward normal of a sphere is its interior, whichever lobe took the
        // path there (refraction, or the opacity pass-through of a cut-out surface).
        state.inside_set = going < 0.0f ? (state.inside_set | slot_bit) : (state.inside_set & ~slot_bit);
    }
    state.origin = position + normal * (going >= 0.0f ? path.epsilon : -path.epsilon);
    state.direction = bsdf_sample.direction;
    if (state.surface_events >= path.roulette_depth)
    {
        openpbr_render_roulette(path.key, state, step);
    }
}

// A surface hit (an object or the ground): a false hit inside a medium of higher priority goes
// straight on; otherwise the surface's BSDF between the media on its two sides gives its
// emission, the next-event estimation and the next direction.
OPENPBR_FUNC void openpbr_render_surface(OPENPBR_IN(OpenPBR_RenderPath) path, OPENPBR_INOUT(OpenPBR_RenderPathState) state,
                                         OPENPBR_IN(OpenPBR_RenderHit) hit, float previous_selection, uint step)
{
    // Geometric normal = shading normal.
    const vec3 position = state.origin + state.direction * hit.t;
    const bool on_object = hit.kind == OPENPBR_RENDER_HIT_OBJECT;
    const uint slot = hit.slot;
    const vec3 normal =
        on_object ? normalize(position - openpbr_render_object_center(path.cell_index, slot)) : vec3(0.0f, 1.0f, 0.0f);
    const bool encloses =
        on_object && openpbr_render_object_float(path.cell_index, slot, OPENPBR_RENDER_OBJECT_ENCLOSES) != 0.0f;
    const uint slot_bit = on_object ? (1u << slot) : 0u;
    // The medium outside this surface: the entered object of highest priority other than
    // the one hit (the environment when there is none).
    const uint outside_object = openpbr_render_top_object(state.inside_set & ~slot_bit);
    if (on_object && outside_object < OPENPBR_RENDER_MAX_OBJECTS && outside_object > slot)
    {
        // A false hit: the surface lies inside a medium of higher priority, which continues
        // on both sides. Straight on; only the membership of the object hit changes.
        const float crossing = dot(state.direction, normal);
        if (encloses)
        {
            state.inside_set = crossing < 0.0f ? (state.inside_set | slot_bit) : (state.inside_set & ~slot_bit);
        }
        state.origin = position + normal * (crossing >= 0.0f ? path.epsilon : -path.epsilon);
        return;
    }
    const float exterior_ior = on_object ? openpbr_render_medium_ior(path.cell_index, outside_object) : 1.0f;
    // The ground's material with its checker, or the object's.
    OpenPBR_ResolvedInputs inputs = path.sphere_inputs;
    if (!on_object)
    {
        inputs = openpbr_render_unpack_material(path.ground_material);
        const float parity = fract(0.5f * (floor(position.x / path.checker_size) + floor(position.z / path.checker_size)));
        inputs.base_color = inputs.base_color * (parity < 0.25f ? 1.0f : path.checker_dark);
    }
    else if (slot != 0u)
    {
        inputs = openpbr_render_unpack_material(
            uint(openpbr_render_object_float(path.cell_index, slot, OPENPBR_RENDER_OBJECT_MATERIAL)));
    }
    inputs.geometry_basis = openpbr_make_basis(normal);
    inputs.geometry_coat_basis = inputs.geometry_basis;
    const vec3 view = -state.direction;
    const OpenPBR_PreparedBsdf bsdf =
        openpbr_prepare(inputs, view, on_object ? path.wavelengths : path.ground_wavelengths, exterior_ior);
    if (on_object)
    {
        openpbr_render_add_emission(path, state, bsdf.emission, slot, previous_selection);
    }

    state.surface_events += 1u;
    if (state.surface_events > path.max_depth)
    {
        state.done = true;
        return;
    }
    const uint candidates = (path.has_light ? OPENPBR_RENDER_EMITTER_LIGHT : 0u) |
                            (!on_object && path.sphere_emissive ? OPENPBR_RENDER_EMITTER_SPHERE : 0u);
    if (candidates != 0u)
    {
        openpbr_render_next_event(path, state, bsdf, position, normal, candidates, step);
    }
    openpbr_render_continue_path(path, state, bsdf, position, normal, encloses, slot_bit, candidates, step);
}

// One step of a path: the closest hit, then a medium event, the escape, the light, or a surface
// (emission, next-event estimation, BSDF sampling, roulette). Sets state.done when the path
// ends; the caller stops after path.step_limit steps at the latest.
OPENPBR_FUNC void openpbr_render_path_step(OPENPBR_IN(OpenPBR_RenderPath) path, OPENPBR_INOUT(OpenPBR_RenderPathState) state)
{
    const uint step = state.step;
    state.step = step + 1u;
    const OpenPBR_HomogeneousVolume medium =
        openpbr_render_medium_volume(path.cell_index, openpbr_render_top_object(state.inside_set));
    const bool in_medium = state.inside_set != 0u;
    const OpenPBR_RenderHit hit = openpbr_render_closest_hit(path, state);
    if (step == 0u)
    {
        state.hit_object = hit.kind == OPENPBR_RENDER_HIT_OBJECT;
    }
    if (in_medium && hit.kind != OPENPBR_RENDER_HIT_OBJECT)
    {
        state.done = true;
        return;  // lost the interior to rounding: end the path (no light gained)
    }
    // Interior medium: free flight to the next scattering event or to the surface.
    if (in_medium && medium.is_present && openpbr_render_medium_flight(path, state, medium, hit.t, step))
    {
        return;
    }

    if (hit.kind == OPENPBR_RENDER_HIT_NONE)
    {
        state.radiance = state.radiance + state.throughput * openpbr_render_environment(state.direction, path.flags);
        state.done = true;
        return;
    }
    const float previous_selection = openpbr_render_emitter_selection(state.previous_candidates);
    if (hit.kind == OPENPBR_RENDER_HIT_LIGHT)
    {
        const float weight =
            (state.previous_candidates & OPENPBR_RENDER_EMITTER_LIGHT) != 0u
                ? openpbr_render_power_heuristic(
                      state.previous_pdf, previous_selection * openpbr_render_cone_pdf(state.previous_position,
                                                                                       path.light_center, path.light_radius))
                : 1.0f;
        state.radiance = state.radiance + state.throughput * path.light_radiance * weight;
        state.done = true;
        return;
    }
    openpbr_render_surface(path, state, hit, previous_selection, step);
}

// The sample a finished (or stopped) path gives.
OPENPBR_FUNC OpenPBR_RenderSample openpbr_render_path_end(OPENPBR_IN(OpenPBR_RenderPathState) state)
{
    OpenPBR_RenderSample result;
    result.hit_object = state.hit_object;
    result.nonfinite = false;
    const vec3 radiance = state.radiance;
    if (state.nonfinite || !openpbr_render_is_finite(radiance) || radiance.x < 0.0f || radiance.y < 0.0f ||
        radiance.z < 0.0f)
    {
        result.nonfinite = true;
        result.radiance = vec3(0.0f);
        return result;
    }
    result.radiance = radiance;
    return result;
}

OPENPBR_FUNC OpenPBR_RenderSample openpbr_render_sample(uint pixel_x, uint pixel_y, uint sample_index)
{
    const OpenPBR_RenderPath path = openpbr_render_path_setup(pixel_x, pixel_y, sample_index);
    OpenPBR_RenderPathState state = openpbr_render_path_begin(path);
    while (!state.done && state.step < path.step_limit)
    {
        openpbr_render_path_step(path, state);
    }
    return openpbr_render_path_end(state);
}

// Adds one sample to the accumulation record that starts at `base` (float sums, so every
// backend that adds the samples of a pixel in sample order gets the same record).
OPENPBR_FUNC void openpbr_render_accumulate(uint base, OPENPBR_IN(OpenPBR_RenderSample) value)
{
    const vec3 sum = vec3(OPENPBR_RENDER_ACCUMULATION_READ(base), OPENPBR_RENDER_ACCUMULATION_READ(base + 1u),
                          OPENPBR_RENDER_ACCUMULATION_READ(base + 2u)) +
                     value.radiance;
    const vec3 sum_squares = vec3(OPENPBR_RENDER_ACCUMULATION_READ(base + 3u), OPENPBR_RENDER_ACCUMULATION_READ(base + 4u),
                                  OPENPBR_RENDER_ACCUMULATION_READ(base + 5u)) +
                             value.radiance * value.radiance;
    const float nonfinite_count = OPENPBR_RENDER_ACCUMULATION_READ(base + 6u) + (value.nonfinite ? 1.0f : 0.0f);
    const float object_count = OPENPBR_RENDER_ACCUMULATION_READ(base + 7u) + (value.hit_object ? 1.0f : 0.0f);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base, sum.x);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 1u, sum.y);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 2u, sum.z);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 3u, sum_squares.x);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 4u, sum_squares.y);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 5u, sum_squares.z);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 6u, nonfinite_count);
    OPENPBR_RENDER_ACCUMULATION_WRITE(base + 7u, object_count);
}

// The accumulation record of a pixel, or OPENPBR_RENDER_NO_PIXEL outside the image.
#define OPENPBR_RENDER_NO_PIXEL 0xffffffffu
OPENPBR_FUNC uint openpbr_render_record(uint pixel_x, uint pixel_y)
{
    const uint width = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_WIDTH);
    const uint height = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_HEIGHT);
    if (pixel_x >= width || pixel_y >= height)
    {
        return OPENPBR_RENDER_NO_PIXEL;
    }
    return (pixel_y * width + pixel_x) * uint(OPENPBR_RENDER_ACCUMULATION_FLOATS);
}

// Adds samples [SAMPLE_BEGIN, SAMPLE_END) of one pixel to its accumulation record, in sample
// order.
OPENPBR_FUNC void openpbr_render_pixel(uint pixel_x, uint pixel_y)
{
    const uint base = openpbr_render_record(pixel_x, pixel_y);
    if (base == OPENPBR_RENDER_NO_PIXEL)
    {
        return;
    }
    const uint sample_end = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_SAMPLE_END);
    for (uint sample_index = OPENPBR_RENDER_PARAMETER(OPENPBR_RENDER_PARAMETER_SAMPLE_BEGIN); sample_index < sample_end;
         ++sample_index)
    {
        openpbr_render_accumulate(base, openpbr_render_sample(pixel_x, pixel_y, sample_index));
    }
}

OPENPBR_NAMESPACE_END

#endif
