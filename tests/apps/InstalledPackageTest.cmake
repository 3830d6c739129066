# Installs the build tree into a scratch prefix, builds an example against it
# with find_package(Strata), and runs the example.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${err}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(path include/strata/Error.h include/strata/terrain/TerrainField.h include/strata/meshing/GridToMesh.h
        include/strata/render/GlRenderer.h lib/cmake/Strata/StrataConfig.cmake bin/strata)
  if(NOT EXISTS ${prefix}/${path})
    message(FATAL_ERROR "install is missing ${path}")
  endif()
endforeach()

run(${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/strata_generator_example ${WORK_DIR}/example.glb)
if(NOT EXISTS ${WORK_DIR}/example.glb)
  message(FATAL_ERROR "the example did not write its mesh")
endif()
message("installed-package example OK")
