// Conformance kernel (WGSL) over the generated library, as a WebGPU engine would use
// openpbr.wgsl: the build appends this file to openpbr.wgsl (WGSL has no #include) and runs
// the result as conformance path "wgsl-library" (targets/wgsl/dispatch_conformance.mjs). It is
// written in WGSL on purpose, by hand, against the library's public names only: the path checks
// that openpbr.wgsl is usable as shipped, which compiling the shared kernel body through Slang
// (path "slang-wgsl") cannot show. Its records and modes are those of
// targets/kernels/openpbr_conformance_kernel.h.
// Bindings (group 0): 0 tables, 1 fuzz table, 3 packed materials (the library's, moved from its
// default 2 when generated: -D OPENPBR_WGSL_MATERIAL_BINDING=3), 2 queries, 4 parameters
// (query count, mode), 5 results.
@group(0) @binding(2) var<storage, read> conformance_queries : array<f32>;
@group(0) @binding(4) var<storage, read> conformance_parameters : array<u32>;
@group(0) @binding(5) var<storage, read_write> conformance_results : array<f32>;

const conformance_query_floats = 11u;
const conformance_result_floats = 24u;
const conformance_mode_all = 0u;
const conformance_mode_eval = 1u;
const conformance_mode_sample = 2u;
const conformance_mode_pdf = 3u;

fn conformance_read_vec3(index : u32) -> vec3<f32>
{
    return vec3<f32>(conformance_queries[index], conformance_queries[index + 1u], conformance_queries[index + 2u]);
}

fn conformance_write_vec3(index : u32, value : vec3<f32>)
{
    conformance_results[index] = value.x;
    conformance_results[index + 1u] = value.y;
    conformance_results[index + 2u] = value.z;
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) thread_id : vec3<u32>)
{
    if (thread_id.x >= conformance_parameters[0]) {
        return;
    }
    let mode = conformance_parameters[1];
    let query = thread_id.x * conformance_query_floats;
    let material_index = u32(conformance_queries[query]);
    let view = conformance_read_vec3(query + 1u);
    let light = conformance_read_vec3(query + 4u);
    let u = conformance_read_vec3(query + 7u);
    let exterior_ior = conformance_queries[query + 10u];

    let bsdf = openpbr_prepare(openpbr_unpack_material(material_index), view, openpbr_default_rgb_wavelengths_nm(),
                               exterior_ior);
    let result = thread_id.x * conformance_result_floats;
    if (mode == conformance_mode_all || mode == conformance_mode_eval) {
        let value = openpbr_eval(bsdf, light);
        conformance_write_vec3(result, value.diffuse);
        conformance_write_vec3(result + 3u, value.specular);
        conformance_write_vec3(result + 18u, bsdf.emission);
    }
    if (mode == conformance_mode_all || mode == conformance_mode_pdf) {
        conformance_results[result + 6u] = openpbr_pdf(bsdf, light);
    }
    if (mode == conformance_mode_all || mode == conformance_mode_sample) {
        let bsdf_sample = openpbr_sample(bsdf, u);
        conformance_write_vec3(result + 7u, bsdf_sample.direction);
        conformance_write_vec3(result + 10u, bsdf_sample.weight.diffuse);
        conformance_write_vec3(result + 13u, bsdf_sample.weight.specular);
        conformance_results[result + 16u] = bsdf_sample.pdf;
        conformance_results[result + 17u] = f32(bsdf_sample.lobe_type);
    }
    if (mode == conformance_mode_all) {
        conformance_results[result + 21u] = 0.0;
        conformance_results[result + 22u] = 0.0;
        conformance_results[result + 23u] = 0.0;
    }
}
