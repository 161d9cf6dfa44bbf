// The body of the conformance kernel, shared by every executed path: the Slang kernel
// (conformance.slang), the GLSL kernel (conformance.comp) and the CPU runner
// (host/checks/conformance.cpp) include this same text, so all paths run identical code.
//
// Record layouts (floats):
//   query  (OPENPBR_QUERY_FLOATS):  material index, view (3), light (3), u (3), exterior IOR
//   result (OPENPBR_RESULT_FLOATS): eval.diffuse (3), eval.specular (3), pdf(light),
//                                   sample.direction (3), sample.weight.diffuse (3),
//                                   sample.weight.specular (3), sample.pdf, sample.lobe_type,
//                                   emission (3), 3 unused
// The includer defines OPENPBR_QUERY_READ(index), OPENPBR_MATERIAL_READ(index) and
// OPENPBR_RESULT_WRITE(index, value) and has the OpenPBR API in scope.
//
// Modes (the second entry of the kernels' parameter buffer; 0 in conformance runs): ALL runs
// and writes everything; the others run prepare plus one operation and write only its slots,
// so `openpbr bench gpu` times each operation on its own (a uniform branch: every thread of a
// dispatch takes the same one).
#ifndef OPENPBR_CONFORMANCE_KERNEL_H
#define OPENPBR_CONFORMANCE_KERNEL_H

#define OPENPBR_QUERY_FLOATS 11
#define OPENPBR_RESULT_FLOATS 24

#define OPENPBR_CONFORMANCE_MODE_ALL 0u
#define OPENPBR_CONFORMANCE_MODE_EVAL 1u    // prepare + eval: slots 0-5, 18-20
#define OPENPBR_CONFORMANCE_MODE_SAMPLE 2u  // prepare + sample: slots 7-17
#define OPENPBR_CONFORMANCE_MODE_PDF 3u     // prepare + pdf: slot 6

#include "../../slang/openpbr_material_packing.h"

OPENPBR_NAMESPACE_BEGIN

OPENPBR_FUNC vec3 openpbr_conformance_read_vec3(uint index)
{
    return vec3(OPENPBR_QUERY_READ(index), OPENPBR_QUERY_READ(index + 1u), OPENPBR_QUERY_READ(index + 2u));
}

OPENPBR_FUNC void openpbr_conformance_write_vec3(uint index, vec3 value)
{
    OPENPBR_RESULT_WRITE(index, value.x);
    OPENPBR_RESULT_WRITE(index + 1u, value.y);
    OPENPBR_RESULT_WRITE(index + 2u, value.z);
}

OPENPBR_FUNC void openpbr_conformance_run_query(uint query_index, uint mode)
{
    const uint query = query_index * uint(OPENPBR_QUERY_FLOATS);
    const uint material_index = uint(OPENPBR_QUERY_READ(query));
    const vec3 view = openpbr_conformance_read_vec3(query + 1u);
    const vec3 light = openpbr_conformance_read_vec3(query + 4u);
    const vec3 u = openpbr_conformance_read_vec3(query + 7u);
    const float exterior_ior = OPENPBR_QUERY_READ(query + 10u);

    const OpenPBR_ResolvedInputs inputs = openpbr_unpack_material(material_index);
    const OpenPBR_PreparedBsdf bsdf = openpbr_prepare(inputs, view, openpbr_default_rgb_wavelengths_nm(), exterior_ior);
    const uint result = query_index * uint(OPENPBR_RESULT_FLOATS);
    if (mode == OPENPBR_CONFORMANCE_MODE_ALL || mode == OPENPBR_CONFORMANCE_MODE_EVAL)
    {
        const OpenPBR_DiffuseSpecular value = openpbr_eval(bsdf, light);
        openpbr_conformance_write_vec3(result, value.diffuse);
        openpbr_conformance_write_vec3(result + 3u, value.specular);
        openpbr_conformance_write_vec3(result + 18u, bsdf.emission);
    }
    if (mode == OPENPBR_CONFORMANCE_MODE_ALL || mode == OPENPBR_CONFORMANCE_MODE_PDF)
    {
        OPENPBR_RESULT_WRITE(result + 6u, openpbr_pdf(bsdf, light));
    }
    if (mode == OPENPBR_CONFORMANCE_MODE_ALL || mode == OPENPBR_CONFORMANCE_MODE_SAMPLE)
    {
        const OpenPBR_BsdfSample bsdf_sample = openpbr_sample(bsdf, u);
        openpbr_conformance_write_vec3(result + 7u, bsdf_sample.direction);
        openpbr_conformance_write_vec3(result + 10u, bsdf_sample.weight.diffuse);
        openpbr_conformance_write_vec3(result + 13u, bsdf_sample.weight.specular);
        OPENPBR_RESULT_WRITE(result + 16u, bsdf_sample.pdf);
        OPENPBR_RESULT_WRITE(result + 17u, float(bsdf_sample.lobe_type));
    }
    if (mode == OPENPBR_CONFORMANCE_MODE_ALL)
    {
        OPENPBR_RESULT_WRITE(result + 21u, 0.0f);
        OPENPBR_RESULT_WRITE(result + 22u, 0.0f);
        OPENPBR_RESULT_WRITE(result + 23u, 0.0f);
    }
}

OPENPBR_NAMESPACE_END

#endif
