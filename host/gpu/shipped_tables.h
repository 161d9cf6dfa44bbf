// The energy-compensation and fuzz tables as compiled into the C++ build (array mode), handed to GPU
// paths as buffer contents: CPU and GPU then read the very same floats.
#pragma once

#include <iterator>
#include <vector>

#include "slang/openpbr.h"

namespace openpbr::host {

inline std::vector<float> shipped_lut()
{
    return std::vector<float>(std::begin(openpbr::openpbr_lut_data), std::end(openpbr::openpbr_lut_data));
}

inline std::vector<float> shipped_fuzz_ltc()
{
    return std::vector<float>(std::begin(openpbr::openpbr_fuzz_ltc_data), std::end(openpbr::openpbr_fuzz_ltc_data));
}

}  // namespace openpbr::host
