// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/LandformGoals.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace strata::terrain {

namespace {

LandformGoal goal(const std::string& name, const std::string& unit, double value, double low, double high)
{
    return {name, unit, value, low, high, value >= low && value <= high};
}

std::string number(double v)
{
    if (!std::isfinite(v)) return "n/a";
    std::ostringstream o;
    o << std::setprecision(3) << v;
    return o.str();
}

} // namespace

std::vector<LandformGoal> checkLandformGoals(const LandformStatistics& stats)
{
    return {
        goal("depressions", "%", 100.0 * stats.depressionFraction, -HUGE_VAL, 8.0),
        goal("flats", "%", 100.0 * stats.flatFraction, -HUGE_VAL, 12.0),
        goal("Hack exponent h", "", stats.hack.exponent, 0.45, 0.7),
        goal("concavity theta", "", stats.concavity, 0.2, 0.8),
        goal("slope-area r^2", "", stats.slopeArea.rSquared, 0.7, HUGE_VAL),
    };
}

std::string formatLandformGoals(const std::vector<LandformGoal>& goals)
{
    std::ostringstream out;
    const auto row = [&out](const std::string& name, const std::string& value, const std::string& range,
                            const std::string& met) {
        out << std::left << std::setw(20) << name << std::setw(12) << value << std::setw(14) << range << met << '\n';
    };
    row("goal", "value", "target", "met");
    std::size_t met = 0;
    for (const LandformGoal& g : goals) {
        const std::string unit = g.unit.empty() ? "" : " " + g.unit;
        std::string range;
        if (std::isinf(g.low))
            range = "<= " + number(g.high) + unit;
        else if (std::isinf(g.high))
            range = ">= " + number(g.low) + unit;
        else
            range = number(g.low) + " - " + number(g.high) + unit;
        row(g.name, number(g.value) + (std::isfinite(g.value) ? unit : ""), range, g.met ? "yes" : "NO");
        met += g.met ? 1 : 0;
    }
    out << met << " of " << goals.size() << " goals met\n";
    return out.str();
}

} // namespace strata::terrain
