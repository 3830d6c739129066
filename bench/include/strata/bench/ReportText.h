// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Small text helpers shared by the bench reports.

#include <filesystem>
#include <string>

namespace strata::bench {

/// `value` with `digits` decimals (printf "%.*f"); "inf" and "-inf" for
/// infinities and "" for NaN (a figure that does not apply).
std::string fixedOrBlank(double value, int digits);

/// `value` with `digits` decimals (printf "%.*f", so NaN prints "nan").
std::string fixedDigits(double value, int digits);

/// Writes `text` to `path` atomically (common/AtomicFile.h). Throws
/// strata::Error (Io) when it cannot.
void writeTextFile(const std::filesystem::path& path, const std::string& text);

} // namespace strata::bench
