# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# `npm ci` of a committed lockfile into a folder of the build tree (never the
# source tree), for cmake -P scripts: the tests' packages (tests/npm/NpmCi.cmake)
# and the web viewer's (web/NpmCi.cmake).
#   strata_npm_ci_folder(<npm> <folder with package.json and package-lock.json>
#                        <modules folder> <timeout seconds> <what to do when it fails>)
# npm runs only when the lockfile differs from the copy MODULES keeps of the
# one it installed; otherwise MODULES is used as it is, offline. A failure
# removes that copy, so the next run tries again.
function(strata_npm_ci_folder npm lock_dir modules timeout hint)
  set(lock "${lock_dir}/package-lock.json")
  if(EXISTS "${modules}/package-lock.json" AND EXISTS "${modules}/node_modules/.package-lock.json")
    file(SHA256 "${lock}" wanted)
    file(SHA256 "${modules}/package-lock.json" have)
    if(wanted STREQUAL have)
      return()
    endif()
  endif()
  file(MAKE_DIRECTORY "${modules}")
  file(COPY "${lock_dir}/package.json" "${lock}" DESTINATION "${modules}")
  execute_process(
    COMMAND "${npm}" ci --no-audit --no-fund --ignore-scripts --loglevel=error
    WORKING_DIRECTORY "${modules}"
    RESULT_VARIABLE npm_result OUTPUT_VARIABLE npm_output ERROR_VARIABLE npm_output TIMEOUT ${timeout})
  if(NOT npm_result EQUAL 0 OR NOT EXISTS "${modules}/node_modules/.package-lock.json")
    file(REMOVE "${modules}/package-lock.json")
    message(FATAL_ERROR "cannot install the npm packages of ${lock} into ${modules} with npm ci (no network?). "
                        "${hint}\n${npm_output}")
  endif()
endfunction()
