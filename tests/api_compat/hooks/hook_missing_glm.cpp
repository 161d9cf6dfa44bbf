// Must NOT compile: a C++ translation unit that includes the BSDF headers below slang/openpbr.h
// without <glm/glm.hpp> first. tests/api_compat/CMakeLists.txt checks that the compiler stops
// with the interop's message naming <glm/glm.hpp> (not with an error deep inside the BSDF).
#include "slang/openpbr_established_api.h"

int main() { return 0; }
