// The api_compat program as HLSL: the generated, self-contained openpbr.hlsl and the program
// spelled in HLSL by the same generator (api_compat_program.hlsl, generate_hlsl.mjs -provided),
// as an HLSL engine would include them. Compiled with glslang's HLSL front end.
#include "openpbr.hlsl"

RWStructuredBuffer<float> api_compat_results : register(u2);
#define API_COMPAT_WRITE(index, value) api_compat_results[index] = (value)
#include "api_compat_program.hlsl"

[numthreads(1, 1, 1)]
void main(uint3 thread_id : SV_DispatchThreadID)
{
    api_compat_shade(openpbr_make_default_resolved_inputs(), float3(0.0f, 0.0f, 1.0f), normalize(float3(0.3f, 0.2f, 0.9f)),
                     float3(1.0f, 0.5f, 0.25f), OpenPBR_VacuumIor, float3(0.3f, 0.6f, 0.9f), float2(0.4f, 0.7f), thread_id.x * API_COMPAT_RESULT_COUNT);
}
