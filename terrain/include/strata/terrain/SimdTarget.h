// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The SIMD instruction set block noise evaluation runs on. Strata compiles
/// its noise kernels for every x86 level Highway knows (SCALAR, SSSE3, SSE4,
/// AVX2, AVX3 = AVX-512) and picks the best the CPU has at run time; every
/// one gives the same bits (checked), so the choice changes speed only.

#include <string>
#include <vector>

namespace strata::terrain {

/// The targets this machine can run, best first: "AVX3", "AVX2", "SSE4",
/// "SSSE3", "SCALAR" (Highway's names).
std::vector<std::string> availableSimdTargets();

/// The target in use now.
std::string simdTarget();

/// Restricts evaluation to the target `name` (one of availableSimdTargets());
/// an empty name returns to the best. For comparing targets (benchmarks, `--simd`): call it
/// while no evaluation runs (a run that straddles the switch gives the same
/// bits, since every target does). Only Strata's noise is affected, not
/// Highway's process-wide choice. Throws strata::Error (BadInput) naming
/// the targets on an unknown name.
void useSimdTarget(const std::string& name);

} // namespace strata::terrain
