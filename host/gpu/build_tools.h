// Where the build put the tools the host runs (set by targets/CMakeLists.txt on openpbr_host):
// the repository root, node, and the native slangc of the CMake cache variable OPENPBR_SLANGC
// (empty: node + targets/slangc.mjs). The defaults, e.g. "node" from the PATH, serve a build
// without them.
#pragma once

#ifndef OPENPBR_COMPILE_SOURCE_DIR
#define OPENPBR_COMPILE_SOURCE_DIR "."
#endif
#ifndef OPENPBR_COMPILE_NODE
#define OPENPBR_COMPILE_NODE "node"
#endif
#ifndef OPENPBR_COMPILE_SLANGC
#define OPENPBR_COMPILE_SLANGC ""
#endif
