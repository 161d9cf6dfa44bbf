// The records the gradient kernels and their C++ callers share (targets/autodiff/gradients.slang,
// targets/autodiff/gradients_gpu.slang, host/gradients and tests/autodiff).
#ifndef OPENPBR_GRADIENT_RECORDS_H
#define OPENPBR_GRADIENT_RECORDS_H

// The value record the CPU gradient code differentiates: OPENPBR_GRADIENT_VALUE_FLOATS floats,
// eval's diffuse part (3) and specular part (3) toward the light, the emission towards the view (3)
// and the pdf of the light (1), at these offsets.
#define OPENPBR_GRADIENT_VALUE_DIFFUSE 0
#define OPENPBR_GRADIENT_VALUE_SPECULAR 3
#define OPENPBR_GRADIENT_VALUE_EMISSION 6
#define OPENPBR_GRADIENT_VALUE_PDF 9
#define OPENPBR_GRADIENT_VALUE_FLOATS 10

// The GPU kernels' records: the conformance kernels' sizes (OPENPBR_QUERY_FLOATS and
// OPENPBR_RESULT_FLOATS of targets/kernels/openpbr_conformance_kernel.h), so the conformance
// dispatchers run them: a query is material index, view (3), light (3), u (3, unused), exterior
// IOR (unused: air); a result 24 floats.
#define OPENPBR_GRADIENT_QUERY_FLOATS 11
#define OPENPBR_GRADIENT_RESULT_FLOATS 24

// The eval cotangent of the prepared kernel: weights of eval's R, G, B (and 0 on the pdf), unequal
// so a channel swapped or dropped shows.
#define OPENPBR_GRADIENT_EVAL_WEIGHTS float4(1.0f, 0.8f, 0.6f, 0.0f)
// The prepared BSDF's fields whose derivative the prepared kernel writes (3 floats each, 6 fields:
// with d/d(light) twice, the 24 floats of a result): the lobe weights eval multiplies and the
// layering factor under the coat.
#define OPENPBR_GRADIENT_PREPARED_FIELDS(X) \
    X(diffuse.single_scatter_a) X(specular.weight) X(metal.weight) X(coat.weight) X(fuzz.weight) X(under_coat_transmitted)

#endif
