// OPENPBR_USE_CUSTOM_SATURATE=1 (C++): the host's own saturate() is the one the BSDF calls.
// Its own program: the BSDF's inline functions here call another saturate than the standard
// build's, which must not meet them in one program.
#include <glm/glm.hpp>

#include <cstdio>

// The renderer's saturate, counting its calls.
namespace {
int host_saturate_calls = 0;
}
inline float saturate(float x)
{
    ++host_saturate_calls;
    return glm::clamp(x, 0.0f, 1.0f);
}
inline glm::vec3 saturate(const glm::vec3& v)
{
    ++host_saturate_calls;
    return glm::clamp(v, glm::vec3(0.0f), glm::vec3(1.0f));
}

#define OPENPBR_USE_CUSTOM_SATURATE 1
#include "slang/openpbr.h"

int main()
{
    using namespace openpbr;
    const OpenPBR_PreparedBsdf prepared =
        openpbr_prepare(openpbr_make_default_resolved_inputs(), glm::vec3(0.0f, 0.0f, 1.0f));
    // The dielectric specular albedo of prepare goes through openpbr_saturate: with the hook
    // ignored the backend's own saturate would run and the count would stay 0.
    std::printf("host saturate called %d times; probability_specular %g\n", host_saturate_calls,
                double(prepared.probability_specular));
    return host_saturate_calls > 0 && prepared.probability_specular > 0.0f ? 0 : 1;
}
