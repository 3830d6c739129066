// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The project's goals for how much a terrain's top surface looks like real
/// land, checked against LandformStatistics: at most 8 % of the interior in
/// closed depressions, at most 12 % flat, Hack's exponent 0.45–0.7, and a
/// slope–area concavity of 0.2–0.8 fitted with r² >= 0.7 (real basins give
/// h ≈ 0.5–0.6 and θ ≈ 0.4–0.6; docs/landform-statistics.md says why).

#include <strata/terrain/LandformStatistics.h>

#include <string>
#include <vector>

namespace strata::terrain {

/// One goal and how a measurement fares against it.
struct LandformGoal
{
    std::string name;   ///< "depressions", "flats", "Hack exponent h", "concavity theta", "slope-area r^2"
    std::string unit;   ///< "%" for the fractions (value, low and high in percent), else empty
    double value = 0.0; ///< the measured value (NaN when the statistic could not be computed)
    double low = 0.0;   ///< the goal's range, both ends included; −infinity or +infinity for one-sided goals
    double high = 0.0;
    bool met = false; ///< low <= value <= high (false for NaN)
};

/// The five goals, in the order above, checked against `stats`.
std::vector<LandformGoal> checkLandformGoals(const LandformStatistics& stats);

/// A readable table of `goals`: one line each with the value, the goal and
/// "yes"/"NO", then a line saying how many are met; ends with a newline.
std::string formatLandformGoals(const std::vector<LandformGoal>& goals);

} // namespace strata::terrain
