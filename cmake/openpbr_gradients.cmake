# Gradients (docs/gradients.md): the differentiable build of the module (OPENPBR_AUTODIFF=1) as
#  - the CPU gradient library openpbr_gradients: Slang's C++ output of
#    targets/autodiff/gradients.slang behind host/gradients/gradients.h, with the material fit
#    (host/gradients/material_fit.h) that `openpbr fit` runs;
#  - the GPU gradient kernels of the autodiff tests (target openpbr_gradient_kernels):
#    targets/autodiff/gradients_gpu.slang as SPIR-V (lavapipe) and WGSL (Dawn).
# Each is generated once per build. Included by the top-level CMakeLists.txt after the kernels'
# set-up and the host libraries.
find_package(Threads REQUIRED)
set(OPENPBR_GRADIENT_DIR ${PROJECT_BINARY_DIR}/gradients)
set(OPENPBR_GRADIENT_CODE ${OPENPBR_GRADIENT_DIR}/openpbr_gradients.cpp)
file(MAKE_DIRECTORY ${OPENPBR_GRADIENT_DIR})
# Slang's C++ source target is slangc.mjs's (-target cpp), native slangc or not.
add_custom_command(
  OUTPUT ${OPENPBR_GRADIENT_CODE}
  COMMAND ${NODE_EXECUTABLE} ${PROJECT_SOURCE_DIR}/targets/slangc.mjs -target cpp -D OPENPBR_AUTODIFF=1
          -D OPENPBR_SPECIALIZATION_CONSTANTS=0 -D OPENPBR_LUT_MODE_ARRAY=1 -I ${PROJECT_SOURCE_DIR}/slang
          -o ${OPENPBR_GRADIENT_CODE} -depfile ${OPENPBR_GRADIENT_CODE}.d
          ${PROJECT_SOURCE_DIR}/targets/autodiff/gradients.slang
  DEPENDS ${PROJECT_SOURCE_DIR}/targets/autodiff/gradients.slang ${PROJECT_SOURCE_DIR}/targets/slangc.mjs
          ${PROJECT_SOURCE_DIR}/targets/source_text.mjs
  DEPFILE ${OPENPBR_GRADIENT_CODE}.d
  COMMENT "slangc cpp: the gradient code (targets/autodiff/gradients.slang)"
  VERBATIM)
add_custom_target(openpbr_gradient_code DEPENDS ${OPENPBR_GRADIENT_CODE})

add_library(openpbr_gradients STATIC host/gradients/gradients.cpp host/gradients/material_fit.cpp)
add_dependencies(openpbr_gradients openpbr_gradient_code)
target_link_libraries(openpbr_gradients PUBLIC openpbr_host_core Threads::Threads)
target_compile_options(openpbr_gradients PRIVATE ${OPENPBR_WARNINGS})
# The generated code is included as a system header (its warnings are Slang's, not the
# project's); gradients.cpp's own code keeps the project's warnings. That one translation unit is
# compiled at -O1 without debug information in every configuration: COMPILE_FIGURES.
target_include_directories(openpbr_gradients SYSTEM PRIVATE ${OPENPBR_GRADIENT_DIR})
set_source_files_properties(host/gradients/gradients.cpp PROPERTIES
  OBJECT_DEPENDS ${OPENPBR_GRADIENT_CODE}
  COMPILE_DEFINITIONS OPENPBR_GRADIENT_CODE=<openpbr_gradients.cpp>
  COMPILE_OPTIONS "-O1;-g0")

# The GPU kernel (eval and pdf with prepared inputs, reverse mode): SPIR-V and WGSL.
set(OPENPBR_GRADIENT_KERNELS ${OPENPBR_KERNEL_DIR}/gradients_gpu.spv ${OPENPBR_KERNEL_DIR}/gradients_gpu.wgsl)
add_custom_command(
  OUTPUT ${OPENPBR_GRADIENT_KERNELS}
  COMMAND ${NODE_EXECUTABLE} ${PROJECT_SOURCE_DIR}/targets/slangc.mjs -target spirv,wgsl -entry gradient_prepared_main -stage compute -D OPENPBR_AUTODIFF=1 -I ${PROJECT_SOURCE_DIR}/slang
          -o ${OPENPBR_KERNEL_DIR} -name gradients_gpu -depfile ${OPENPBR_KERNEL_DIR}/gradients_gpu.d
          ${PROJECT_SOURCE_DIR}/targets/autodiff/gradients_gpu.slang
  DEPENDS ${PROJECT_SOURCE_DIR}/targets/autodiff/gradients_gpu.slang ${PROJECT_SOURCE_DIR}/targets/slangc.mjs
          ${PROJECT_SOURCE_DIR}/targets/source_text.mjs
  DEPFILE ${OPENPBR_KERNEL_DIR}/gradients_gpu.d
  COMMENT "slangc spirv,wgsl: the GPU gradient kernels (targets/autodiff/gradients_gpu.slang)"
  VERBATIM)
add_custom_target(openpbr_gradient_kernels DEPENDS ${OPENPBR_GRADIENT_KERNELS})  # test_gradients_gpu's
