// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The project's landform goals: each checked against its range, ends
// included, NaN never met; the table shows every goal.

#include <strata/terrain/LandformGoals.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

using namespace strata::terrain;

LandformStatistics realistic()
{
    LandformStatistics s;
    s.depressionFraction = 0.08; // ends of the ranges count as met
    s.flatFraction = 0.05;
    s.hack.exponent = 0.45;
    s.concavity = 0.8;
    s.slopeArea.rSquared = 0.7;
    return s;
}

TEST(LandformGoals, EachGoalAgainstItsRange)
{
    const std::vector<LandformGoal> goals = checkLandformGoals(realistic());
    ASSERT_EQ(goals.size(), 5u);
    for (const LandformGoal& g : goals) EXPECT_TRUE(g.met) << g.name;
    EXPECT_EQ(goals[0].name, "depressions");
    EXPECT_DOUBLE_EQ(goals[0].value, 8.0);
    EXPECT_EQ(goals[0].unit, "%");

    LandformStatistics bad = realistic();
    bad.depressionFraction = 0.0801;
    bad.flatFraction = 0.13;
    bad.hack.exponent = 0.71;
    bad.concavity = 0.19;
    bad.slopeArea.rSquared = 0.69;
    for (const LandformGoal& g : checkLandformGoals(bad)) EXPECT_FALSE(g.met) << g.name;

    LandformStatistics none = realistic();
    none.hack.exponent = NAN;
    none.concavity = NAN;
    none.slopeArea.rSquared = NAN;
    const std::vector<LandformGoal> missing = checkLandformGoals(none);
    EXPECT_TRUE(missing[0].met);
    EXPECT_FALSE(missing[2].met);
    EXPECT_FALSE(missing[3].met);
    EXPECT_FALSE(missing[4].met);
}

TEST(LandformGoals, TableShowsEveryGoal)
{
    LandformStatistics s = realistic();
    s.concavity = NAN;
    const std::string table = formatLandformGoals(checkLandformGoals(s));
    for (const char* text :
         {"depressions", "8 %", "<= 8 %", "flats", "<= 12 %", "Hack exponent h", "0.45 - 0.7", "concavity theta", "n/a",
          "0.2 - 0.8", "slope-area r^2", ">= 0.7", "NO", "4 of 5 goals met"}) {
        EXPECT_NE(table.find(text), std::string::npos) << text << " in\n" << table;
    }
}

} // namespace
