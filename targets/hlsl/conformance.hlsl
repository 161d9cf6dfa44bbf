// Conformance kernel (HLSL): the generated openpbr.hlsl, #included as a D3D engine would, and
// the shared kernel body (targets/kernels/openpbr_conformance_kernel.h, spelled in HLSL by the
// same generator as openpbr_conformance_kernel.hlsl). Compiled here with glslang's HLSL front
// end and executed on Vulkan as conformance path "hlsl":
//   glslangValidator -D -V --target-env vulkan1.2 -S comp -e main --hlsl-iomap -o conformance.hlsl.spv conformance.hlsl
// Registers = Vulkan bindings (set 0): t0 tables, t1 fuzz table (openpbr.hlsl's defaults),
// t2 queries, t3 packed materials, t4 parameters (query count), u5 results.
StructuredBuffer<float> conformance_queries : register(t2);
StructuredBuffer<float> conformance_materials : register(t3);
StructuredBuffer<uint> conformance_parameters : register(t4);
RWStructuredBuffer<float> conformance_results : register(u5);

#define OPENPBR_QUERY_READ(index) conformance_queries[index]
#define OPENPBR_MATERIAL_READ(index) conformance_materials[index]
#define OPENPBR_RESULT_WRITE(index, value) conformance_results[index] = (value)
#include "openpbr.hlsl"
#include "openpbr_conformance_kernel.hlsl"

[numthreads(64, 1, 1)]
void main(uint3 thread_id : SV_DispatchThreadID)
{
    if (thread_id.x < conformance_parameters[0])
    {
        openpbr_conformance_run_query(thread_id.x, conformance_parameters[1]);
    }
}
