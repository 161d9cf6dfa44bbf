// The WGSL consumer's kernel (examples/wgsl_consumer): appended to the installed openpbr.wgsl
// (WGSL has no #include), as a WebGPU engine would. One thread per sample: a white rough metal
// seen at a fixed view, one BSDF sample each, its weight and its consistency with eval and pdf
// at the sampled direction written for consumer.mjs to check.
// Bindings (group 0): 0, 1 the library's tables; 3 parameters (sample count), 4 results.
@group(0) @binding(3) var<storage, read> consumer_parameters : array<u32>;
@group(0) @binding(4) var<storage, read_write> consumer_results : array<f32>;

// A 32-bit integer hash (a multiply-xorshift mix), three decorrelated uniforms in [0, 1).
fn consumer_hash(value : u32) -> u32
{
    var x = value;
    x = (x ^ (x >> 16u)) * 0x7feb352du;
    x = (x ^ (x >> 15u)) * 0x846ca68bu;
    return x ^ (x >> 16u);
}

fn consumer_uniform(value : u32) -> f32
{
    return f32(consumer_hash(value) >> 8u) * (1.0 / 16777216.0);
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) thread_id : vec3<u32>)
{
    if (thread_id.x >= consumer_parameters[0]) {
        return;
    }
    var inputs = openpbr_make_default_resolved_inputs();
    inputs.base_color = vec3<f32>(1.0, 1.0, 1.0);
    inputs.base_metalness = 1.0;
    inputs.specular_roughness = 0.5;
    let view = normalize(vec3<f32>(0.6, 0.0, 0.8));
    let bsdf = openpbr_prepare(inputs, view, openpbr_default_rgb_wavelengths_nm(), 1.0);
    let index = thread_id.x * 3u;
    let u = vec3<f32>(consumer_uniform(index), consumer_uniform(index + 1u), consumer_uniform(index + 2u));
    let bsdf_sample = openpbr_sample(bsdf, u);
    let weight = bsdf_sample.weight.diffuse + bsdf_sample.weight.specular;
    // eval / pdf at the sampled direction: equal to the sample's weight for a continuous lobe.
    let value = openpbr_eval(bsdf, bsdf_sample.direction);
    let pdf = openpbr_pdf(bsdf, bsdf_sample.direction);
    let result = thread_id.x * 4u;
    consumer_results[result] = weight.g;
    consumer_results[result + 1u] = bsdf_sample.pdf;
    consumer_results[result + 2u] = select(0.0, (value.diffuse.g + value.specular.g) / pdf, pdf > 0.0);
    consumer_results[result + 3u] = f32(bsdf_sample.lobe_type);
}
