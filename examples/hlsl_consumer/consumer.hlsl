// An HLSL consumer kernel over the installed HLSL library: `#include "openpbr.hlsl"` with
// <prefix>/include/openpbr/hlsl on the include path, compiled here with glslang's HLSL front end
// (examples/hlsl_consumer/CMakeLists.txt); DXC takes the same file. One thread per query, the
// result layout of examples/consumer_common/openpbr_consumer.h.
// Registers = Vulkan bindings (set 0): t0 tables, t1 fuzz table (openpbr.hlsl's defaults),
// t2 queries, t3 packed materials, t4 the query count, u5 results.
StructuredBuffer<float> consumer_queries : register(t2);
StructuredBuffer<float> consumer_materials : register(t3);
StructuredBuffer<uint> consumer_parameters : register(t4);
RWStructuredBuffer<float> consumer_results : register(u5);

// openpbr.hlsl defines openpbr_unpack_material when the material read is defined first.
#define OPENPBR_MATERIAL_READ(index) consumer_materials[index]
#include "openpbr.hlsl"

[numthreads(64, 1, 1)]
void main(uint3 thread_id : SV_DispatchThreadID)
{
    const uint query = thread_id.x;
    if (query >= consumer_parameters[0])
    {
        return;
    }
    const uint q = query * 16u;
    const float3 view = float3(consumer_queries[q], consumer_queries[q + 1u], consumer_queries[q + 2u]);
    const float3 light = float3(consumer_queries[q + 4u], consumer_queries[q + 5u], consumer_queries[q + 6u]);
    const float3 u = float3(consumer_queries[q + 8u], consumer_queries[q + 9u], consumer_queries[q + 10u]);
    const OpenPBR_ResolvedInputs material = openpbr_unpack_material(uint(consumer_queries[q + 12u]));

    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(material, view);
    const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, light);
    const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(bsdf, u);
    const float3 weight = bsdf_sample.weight.diffuse + bsdf_sample.weight.specular;
    consumer_results[q + 0u] = value.diffuse.x;
    consumer_results[q + 1u] = value.diffuse.y;
    consumer_results[q + 2u] = value.diffuse.z;
    consumer_results[q + 3u] = openpbr_pdf(bsdf, light);
    consumer_results[q + 4u] = value.specular.x;
    consumer_results[q + 5u] = value.specular.y;
    consumer_results[q + 6u] = value.specular.z;
    consumer_results[q + 7u] = 0.0f;
    consumer_results[q + 8u] = bsdf_sample.direction.x;
    consumer_results[q + 9u] = bsdf_sample.direction.y;
    consumer_results[q + 10u] = bsdf_sample.direction.z;
    consumer_results[q + 11u] = bsdf_sample.pdf;
    consumer_results[q + 12u] = weight.x;
    consumer_results[q + 13u] = weight.y;
    consumer_results[q + 14u] = weight.z;
    consumer_results[q + 15u] = float(bsdf_sample.lobe_type);
}
