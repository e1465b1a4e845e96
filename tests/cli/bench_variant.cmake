# `facesketch bench contours --pass1/--pass2`: the built-in kernels compiled again from their
# GLSL, given as variants, must give the identical cloud; a missing SPIR-V file must fail with
# exit code 1 naming the file. Every benchmark also reports the hypervisor's steal time.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
foreach(kernel contours_radial contours)
  execute_process(COMMAND ${GLSLANG} -V --target-env vulkan1.2 -S comp -I${SHADERS} -o ${WORK}/${kernel}.spv
                          ${SHADERS}/${kernel}.comp.glsl RESULT_VARIABLE rc OUTPUT_VARIABLE log)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "glslangValidator failed on ${kernel}: ${log}")
  endif()
endforeach()
execute_process(COMMAND ${FACESKETCH} bench contours --meshes 4 --vertices 900 --repeat 1
                        --pass1 ${WORK}/contours_radial.spv --pass2 ${WORK}/contours.spv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "bench failed (${rc}): ${err}")
endif()
if(NOT out MATCHES "candidates_gpu_ab_variant_[0-9]+v_ms [0-9.]+ ms" OR NOT out MATCHES "the variant's cloud is identical to the built-in one \\(([1-9][0-9]*) points\\)")
  message(FATAL_ERROR "unexpected output:\n${out}")
endif()
if(NOT out MATCHES "largest difference of a point: 0 mm in the world, 0 px on the screen")
  message(FATAL_ERROR "the same kernels placed points differently:\n${out}")
endif()
if(EXISTS /proc/stat AND NOT out MATCHES "# contours: [0-9.e+-]+% of the machine's CPU time was stolen by the hypervisor")
  message(FATAL_ERROR "no steal figure in:\n${out}")
endif()
execute_process(COMMAND ${FACESKETCH} bench contours --meshes 4 --vertices 900 --repeat 1 --pass1 ${WORK}/missing.spv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "missing.spv: cannot open the SPIR-V file")
  message(FATAL_ERROR "expected exit code 1 naming missing.spv, got ${rc}: ${err}")
endif()
