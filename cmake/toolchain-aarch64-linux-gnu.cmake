# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Cross-compiling Strata for aarch64 with Debian's g++-aarch64-linux-gnu
# against a folder of arm64 Debian packages (STRATA_ARM64_SYSROOT, made by
# scripts/determinism-builds.sh with mmdebstrap --variant=extract), the
# programs run under qemu-user (docs/determinism.md). Only for the golden
# table's check: apps, Python and the viewer are not built.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

if(NOT STRATA_ARM64_SYSROOT)
  set(STRATA_ARM64_SYSROOT "$ENV{STRATA_ARM64_SYSROOT}")
endif()
if(NOT IS_DIRECTORY "${STRATA_ARM64_SYSROOT}/usr/include")
  message(FATAL_ERROR "STRATA_ARM64_SYSROOT='${STRATA_ARM64_SYSROOT}' is not an arm64 package folder "
                      "(scripts/determinism-builds.sh makes one)")
endif()
set(CMAKE_SYSROOT "${STRATA_ARM64_SYSROOT}")
# try_compile projects see it too (re-runs of cmake have no environment).
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES STRATA_ARM64_SYSROOT)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_FIND_ROOT_PATH "${STRATA_ARM64_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# The sysroot's shared libraries name their own dependencies by soname.
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${STRATA_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu -Wl,-rpath-link,${STRATA_ARM64_SYSROOT}/lib/aarch64-linux-gnu -Wl,-rpath-link,${STRATA_ARM64_SYSROOT}/usr/lib")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "${CMAKE_EXE_LINKER_FLAGS_INIT}")
# pkg-config (libepoxy) reads the sysroot's .pc files.
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${STRATA_ARM64_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR} "${STRATA_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${STRATA_ARM64_SYSROOT}/usr/share/pkgconfig")
# ctest and gtest_discover_tests run the programs through qemu-user, with
# the sysroot's own loader and libraries.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L "${STRATA_ARM64_SYSROOT}")
