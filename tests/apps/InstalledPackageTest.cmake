# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Installs the build tree into a scratch prefix, builds an example against it
# with find_package(Strata), and runs the example. By default the generator
# example; another one with -DEXAMPLE_PROGRAM=<target> -DEXAMPLE_ARGS=<a;b>
# -DEXAMPLE_OUTPUT=<file it must write>.
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
        include/strata/render/GlRenderer.h include/strata/world/World.h include/strata/scene/Pipeline.h lib/cmake/Strata/StrataConfig.cmake bin/strata)
  if(NOT EXISTS ${prefix}/${path})
    message(FATAL_ERROR "install is missing ${path}")
  endif()
endforeach()
# The licence, the third-party notices and every licence text (issue 31).
foreach(path LICENSE THIRD_PARTY.md LICENSES/MIT.txt LICENSES/GPL-2.0-only.txt LICENSES/GPL-2.0-or-later.txt
        LICENSES/LicenseRef-UFOAI-public-domain.txt)
  if(NOT EXISTS ${prefix}/share/doc/strata/${path})
    message(FATAL_ERROR "install is missing share/doc/strata/${path}")
  endif()
endforeach()
file(READ ${prefix}/share/doc/strata/LICENSE licence)
string(FIND "${licence}" "Copyright (c) The Strata authors" at)
if(NOT licence MATCHES "^MIT License\n" OR at EQUAL -1)
  message(FATAL_ERROR "share/doc/strata/LICENSE is not Strata's MIT licence:\n${licence}")
endif()

run(${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
if(NOT DEFINED EXAMPLE_PROGRAM)
  set(EXAMPLE_PROGRAM strata_generator_example)
  set(EXAMPLE_ARGS ${WORK_DIR}/example.glb)
  set(EXAMPLE_OUTPUT ${WORK_DIR}/example.glb)
endif()
run(${WORK_DIR}/build/${EXAMPLE_PROGRAM} ${EXAMPLE_ARGS})
if(NOT EXISTS ${EXAMPLE_OUTPUT})
  message(FATAL_ERROR "the example did not write ${EXAMPLE_OUTPUT}")
endif()
# Optionally: the installed strata CLI writes the same bytes as the example
# (-DCLI_ARGS=<a;b> run as `strata CLI_ARGS`, then each of -DSAME_FILES=<f;g>
# compared between -DCLI_DIR and -DEXAMPLE_DIR_OUT).
if(DEFINED CLI_ARGS)
  run(${prefix}/bin/strata ${CLI_ARGS})
  foreach(file ${SAME_FILES})
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${CLI_DIR}/${file} ${EXAMPLE_DIR_OUT}/${file}
                    RESULT_VARIABLE differ)
    if(NOT differ EQUAL 0)
      message(FATAL_ERROR "${file} differs between `strata ${CLI_ARGS}` and the example")
    endif()
    message("${file}: the same bytes from the CLI and the example")
  endforeach()
endif()
message("installed-package example OK")
