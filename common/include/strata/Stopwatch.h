// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Wall-clock timing of stages, for logs, reports and benchmarks.

#include <chrono>

namespace strata {

/// Started on construction; seconds() reads it, restart() starts it again.
class Stopwatch
{
public:
    double seconds() const { return std::chrono::duration<double>(Clock::now() - mStart).count(); }
    void restart() { mStart = Clock::now(); }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point mStart = Clock::now();
};

} // namespace strata
