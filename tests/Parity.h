// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// GL versus CPU parity thresholds (issue 30): each test holds its PSNR to the
// value measured on CI's GL, less PARITY_MARGIN_DB, so that a regression of
// more than the margin fails instead of hiding under a loose round number.
//
// Every measured value was taken on PARITY_MACHINE (the CI kind of machine;
// llvmpipe's output is byte-identical run to run and across thread counts,
// and each value was measured twice). When a change moves a value on
// purpose, re-measure: each check prints "[ parity   ] NAME: PSNR X dB"
// (grep the test output for it) and update the value beside the check.

#include <gtest/gtest.h>

#include <iomanip>
#include <iostream>
#include <string>

namespace strata::test {

/// Where the measured values come from.
inline constexpr const char* PARITY_MACHINE =
    "Mesa 22.3.6 llvmpipe (LLVM 15) through EGL, Debian 12, AMD EPYC (AVX-512), 2 cores";

/// How far below its measured value a test's PSNR may fall: 3 dB, about 1.4x
/// the mean squared error (the issue allows at most 6 dB).
inline constexpr double PARITY_MARGIN_DB = 3.0;

/// The floor a test asserts for a PSNR measured at `measuredDb` on PARITY_MACHINE.
constexpr double parityFloor(double measuredDb) { return measuredDb - PARITY_MARGIN_DB; }

/// Prints the PSNR `db` of check `name` with its measured value and floor.
inline void printParity(double db, double measuredDb, const std::string& name)
{
    std::cout << "[ parity   ] " << name << ": PSNR " << std::fixed << std::setprecision(2) << db << " dB (measured "
              << measuredDb << " dB, floor " << parityFloor(measuredDb) << " dB)" << std::defaultfloat << std::endl;
}

} // namespace strata::test

/// Expects the PSNR `db` of check `name` to be at least parityFloor(measuredDb),
/// and prints it. `measuredDb` is the value measured on PARITY_MACHINE.
#define STRATA_EXPECT_PARITY(db, measuredDb, name)                                                                   \
    do {                                                                                                             \
        const double strataParityDb_ = (db);                                                                         \
        ::strata::test::printParity(strataParityDb_, (measuredDb), (name));                                          \
        EXPECT_GE(strataParityDb_, ::strata::test::parityFloor(measuredDb))                                          \
            << (name) << ": measured " << (measuredDb) << " dB on " << ::strata::test::PARITY_MACHINE;               \
    } while (false)
