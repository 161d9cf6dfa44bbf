// The working colour space: the RGB space of every colour the BSDF reads (base_color,
// emission_color, ...) and of every value it returns (eval, sample weights, emission). The
// BSDF's colour-dependent constants follow from it: the luminance weights of lobe selection,
// the wavelengths the channels stand for (dispersion), the thin film's spectral sensitivities
// (slang/generated/openpbr_working_space_constants.h, derived from the CIE 1931 observer, the
// primaries and the white point by tools/make_colour_tables.py; docs/colour.md).
//
// OPENPBR_WORKING_SPACE, a compile-time setting:
//   OPENPBR_WORKING_SPACE_ACESCG      ACEScg: linear, ACES AP1 primaries, ACES white (default)
//   OPENPBR_WORKING_SPACE_LIN_REC709  linear Rec.709 / sRGB primaries, D65 white
// e.g. -DOPENPBR_WORKING_SPACE=OPENPBR_WORKING_SPACE_LIN_REC709 on the compiler's command line
// (C++, CUDA, glslang, dxc, slangc). ACEScg is the default because it is the specification's
// ("Metadata": colours are ACEScg unless stated; every OpenPBR example file declares it), and
// because it is the wider space: a Rec.709 colour converts into AP1 with no component outside
// [0, 1], while an AP1 colour converted to Rec.709 can go negative and would have to be
// clipped, changing its hue before the BSDF sees it.
//
// A define, not a specialization constant: the host converts the file's colours into the
// working space and the display converts out of it, so one program has one working space,
// fixed when it is built; a define reaches every language the same way (C++, CUDA and HLSL have
// no specialization constants) and leaves one set of constants in the code, where a
// specialization constant would keep both sets and select between them in the film's inner
// loop. A Slang `import openpbr;` user passes the define to slangc with the other options of
// the compile that imports the module (-DOPENPBR_WORKING_SPACE=OPENPBR_WORKING_SPACE_LIN_REC709):
// the module is compiled from source by that compile, so the define reaches it; a #define in the
// importing file does not cross the import. The module exports OPENPBR_WORKING_SPACE and the
// two values as constants, so the program can check which space it was given.
#ifndef OPENPBR_WORKING_SPACE_H
#define OPENPBR_WORKING_SPACE_H

#define OPENPBR_WORKING_SPACE_LIN_REC709 0
#define OPENPBR_WORKING_SPACE_ACESCG 1

#ifndef OPENPBR_WORKING_SPACE
#define OPENPBR_WORKING_SPACE OPENPBR_WORKING_SPACE_ACESCG
#endif

#include "generated/openpbr_working_space_constants.h"

#endif
