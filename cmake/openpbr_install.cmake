# install() rules and the CMake package `openpbr` (README "Integrating"). Included by the
# top-level CMakeLists.txt after the targets it installs. Layout under the prefix:
#   include/openpbr/slang/...          the single source (C++/GLSL/CUDA/Metal headers) and the
#                                      Slang module (openpbr.slang: `import openpbr;` with this
#                                      folder on the Slang include path)
#   include/openpbr/slang/generated/   the tables: openpbr_lut.bin, openpbr_fuzz_ltc.bin (raw
#                                      little-endian float32) and the same values as C arrays
#                                      (*_values.inc) for the headers' array mode
#   include/openpbr/interop/...        the interop macro layer the headers include
#   include/openpbr/hlsl/openpbr.hlsl  the HLSL library (host build only: generated with node)
#   include/openpbr/wgsl/openpbr.wgsl  the WGSL library for WebGPU (host build only: generated
#                                      with node, targets/wgsl/generate_wgsl.mjs)
#   include/openpbr/host/gpu/vulkan_runner.h, lib/libopenpbr_vulkan_runner.a
#                                      the Vulkan compute runner (host build only)
#   lib/cmake/openpbr/                 openpbrConfig.cmake, its version file, the exported targets
if(NOT OPENPBR_INSTALL)
  return()
endif()
include(CMakePackageConfigHelpers)

# The single source, the Slang module and the tables' tracked form from slang/: the headers
# include their tables as generated/*.inc.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/slang/ DESTINATION ${OPENPBR_INSTALL_INCLUDEDIR}/slang
  FILES_MATCHING PATTERN "*.h" PATTERN "*.inc" PATTERN "*.slang")
# The tables' binary form, which GPU callers upload as generated/*.bin: derived from the .inc
# into the build tree (top-level CMakeLists.txt, "Tables"), listed in OPENPBR_GENERATED_TABLE_FILES.
if(OPENPBR_GENERATED_TABLE_FILES)
  install(FILES ${OPENPBR_GENERATED_TABLE_FILES} DESTINATION ${OPENPBR_INSTALL_INCLUDEDIR}/slang/generated)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/interop/ DESTINATION ${OPENPBR_INSTALL_INCLUDEDIR}/interop
  FILES_MATCHING PATTERN "*.h")

install(TARGETS openpbr EXPORT openpbr_targets)
install(EXPORT openpbr_targets NAMESPACE openpbr:: FILE openpbrTargets.cmake
  DESTINATION ${OPENPBR_INSTALL_CMAKEDIR})

# The host build's installable parts: the Vulkan runner (component vulkan_runner, its own export
# set so that a headers-only consumer never needs Vulkan) and the generated HLSL library.
if(TARGET openpbr_vulkan_runner)
  install(TARGETS openpbr_vulkan_runner EXPORT openpbr_vulkan_runner_targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/host/gpu/vulkan_runner.h
    DESTINATION ${OPENPBR_INSTALL_INCLUDEDIR}/host/gpu)
  install(EXPORT openpbr_vulkan_runner_targets NAMESPACE openpbr:: FILE openpbrVulkanRunnerTargets.cmake
    DESTINATION ${OPENPBR_INSTALL_CMAKEDIR})
endif()
if(OPENPBR_HLSL_LIBRARY_FILE)
  install(FILES ${OPENPBR_HLSL_LIBRARY_FILE} DESTINATION ${OPENPBR_INSTALL_INCLUDEDIR}/hlsl)
endif()
if(OPENPBR_WGSL_LIBRARY_FILE)
  install(FILES ${OPENPBR_WGSL_LIBRARY_FILE} DESTINATION ${OPENPBR_INSTALL_INCLUDEDIR}/wgsl)
endif()

# glm::glm is part of openpbr::openpbr's interface only when this build found GLM; the package
# then looks for it again on the consumer's side.
set(OPENPBR_PACKAGE_NEEDS_GLM OFF)
if(TARGET glm::glm)
  set(OPENPBR_PACKAGE_NEEDS_GLM ON)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/openpbrConfig.cmake.in
  ${PROJECT_BINARY_DIR}/openpbrConfig.cmake
  INSTALL_DESTINATION ${OPENPBR_INSTALL_CMAKEDIR}
  PATH_VARS OPENPBR_INSTALL_INCLUDEDIR)
# SameMajorVersion: a request for 1.0 or 1.1 accepts this 1.1.1, a request for 2.0 does not.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/openpbrConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/openpbrConfig.cmake ${PROJECT_BINARY_DIR}/openpbrConfigVersion.cmake
  DESTINATION ${OPENPBR_INSTALL_CMAKEDIR})
