// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Runs the strata executable (STRATA_EXECUTABLE, set by CMake) as a user
// would, capturing its exit code and everything it printed.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>

/// The first statement of a test that runs the strata program: skips the
/// test in a build without the program (-DSTRATA_BUILD_APPS=OFF, as the
/// sanitizer build is: the program only parses flags around the library
/// calls tested there). runStrata() fails a test that did not say so.
#ifdef STRATA_EXECUTABLE
#define STRATA_REQUIRE_PROGRAM() static_cast<void>(0)
#else
#define STRATA_REQUIRE_PROGRAM() GTEST_SKIP() << "built without the strata program (STRATA_BUILD_APPS=OFF)"
#endif

namespace strata::test {

struct CommandResult
{
    int exitCode;
    std::string output; // stdout and stderr
};

/// `strata ARGUMENTS` with `environment` ("NAME=VALUE ...", may be empty) set
/// for the command only, the output captured through a log file in `dir`.
inline CommandResult runStrataWithEnvironment(const std::string& environment, const std::string& arguments,
                                              const std::filesystem::path& dir)
{
#ifndef STRATA_EXECUTABLE
    ADD_FAILURE() << "this test runs the strata program: begin it with STRATA_REQUIRE_PROGRAM()";
    return {-1, ""};
#else
    const std::filesystem::path log = dir / "command.log";
    const std::string command = (environment.empty() ? "" : "env " + environment + " ") +
                                std::string(STRATA_EXECUTABLE) + " " + arguments + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    std::filesystem::remove(log);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
#endif
}

/// `strata ARGUMENTS`, with the output captured through a log file in `dir`.
inline CommandResult runStrata(const std::string& arguments, const std::filesystem::path& dir)
{
    return runStrataWithEnvironment("", arguments, dir);
}

} // namespace strata::test
