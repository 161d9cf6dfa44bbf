#version 450
// Conformance kernel (GLSL) with texture tables (OPENPBR_USE_TEXTURE_LUTS=1): the tables are
// the combined image samplers the library declares at bindings 6-14 (table id + 6,
// slang/openpbr_lut_textures.h); queries, materials, parameters and results as in
// conformance.comp (bindings 2-5; no table buffers).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#define OPENPBR_LANGUAGE_TARGET_GLSL 1
#define OPENPBR_USE_TEXTURE_LUTS 1
#define OPENPBR_LUT_TEXTURES_DECLARE 1
#include "../../slang/openpbr.h"

layout(std430, set = 0, binding = 2) readonly buffer ConformanceQueries { float conformance_queries[]; };
layout(std430, set = 0, binding = 3) readonly buffer ConformanceMaterials { float conformance_materials[]; };
layout(std430, set = 0, binding = 4) readonly buffer ConformanceParameters { uint conformance_parameters[]; };
layout(std430, set = 0, binding = 5) writeonly buffer ConformanceResults { float conformance_results[]; };

#define OPENPBR_QUERY_READ(index) conformance_queries[index]
#define OPENPBR_MATERIAL_READ(index) conformance_materials[index]
#define OPENPBR_RESULT_WRITE(index, value) conformance_results[index] = (value)
#include "openpbr_conformance_kernel.h"

void main()
{
    if (gl_GlobalInvocationID.x < conformance_parameters[0])
    {
        openpbr_conformance_run_query(gl_GlobalInvocationID.x, conformance_parameters[1]);
    }
}
