// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/terrain/Lithology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

using namespace strata::terrain;

namespace {

LithologyOptions threeBeds(double datum = 100.0)
{
    LithologyOptions o;
    o.beds = {{4.0, 0.9}, {10.0, 0.2}, {2.0, 0.6}}; // period 16
    o.datum = datum;
    o.transition = 0.5;
    return o;
}

void expectErrorNaming(const std::function<void()>& run, const std::string& key)
{
    try {
        run();
        ADD_FAILURE() << "no strata::Error for " << key;
    } catch (const strata::Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(key, 0), 0u) << "message: " << e.what();
    }
}

std::uint64_t lcg(std::uint64_t& state)
{
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 11;
}

double uniform(std::uint64_t& state, double lo, double hi) { return lo + (hi - lo) * double(lcg(state)) * 0x1.0p-53; }

} // namespace

TEST(Lithology, BedsLieWhereTheThicknessesPutThem)
{
    // The first bed's base at the datum, the sequence repeating every 16 m
    // up and down; away from the contacts each bed has its own hardness,
    // at a contact the mean of the two, the same 1e9 m away.
    for (const double datum : {100.0, 1e9}) {
        SCOPED_TRACE(datum);
        const Lithology rock(1, threeBeds(datum));
        const auto at = [&](double y) { return glm::dvec3(3.0, datum + y, -7.0); };
        EXPECT_EQ(rock.bed(at(2.0)), 0);
        EXPECT_EQ(rock.hardness(at(2.0)), 0.9);
        EXPECT_EQ(rock.bed(at(9.0)), 1);
        EXPECT_EQ(rock.hardness(at(9.0)), 0.2);
        EXPECT_EQ(rock.bed(at(15.0)), 2);
        EXPECT_EQ(rock.hardness(at(15.0)), 0.6);
        EXPECT_EQ(rock.bed(at(16.0 + 2.0)), 0);  // the next period
        EXPECT_EQ(rock.bed(at(-1.0)), 2);         // the one below
        EXPECT_EQ(rock.bed(at(-16.0 * 40 + 9.0)), 1);
        EXPECT_NEAR(rock.hardness(at(4.0)), 0.55, 1e-6);  // contact bed 0 / bed 1
        EXPECT_NEAR(rock.hardness(at(16.0)), 0.75, 1e-6); // contact bed 2 / next bed 0
        // Within the transition, between the two; outside it, the bed's own.
        const double h = rock.hardness(at(4.1));
        EXPECT_GT(h, 0.2);
        EXPECT_LT(h, 0.55);
        EXPECT_EQ(rock.hardness(at(4.3)), 0.2);
        EXPECT_EQ(rock.hardness(at(3.7)), 0.9);
    }
}

TEST(Lithology, WithoutRepeatTheEndBedsExtend)
{
    LithologyOptions o = threeBeds(0.0);
    o.repeat = false;
    const Lithology rock(1, o);
    EXPECT_EQ(rock.bed({0.0, -500.0, 0.0}), 0);
    EXPECT_EQ(rock.hardness({0.0, -500.0, 0.0}), 0.9);
    EXPECT_EQ(rock.hardness({0.0, 0.0, 0.0}), 0.9); // no contact at the base
    EXPECT_EQ(rock.bed({0.0, 500.0, 0.0}), 2);
    EXPECT_EQ(rock.hardness({0.0, 16.0, 0.0}), 0.6); // nor at the top
}

TEST(Lithology, ZeroThicknessBedsAreAbsentAndOneBedIsUniform)
{
    LithologyOptions o;
    o.beds = {{0.0, 0.1}, {5.0, 0.7}, {0.0, 0.3}};
    for (const bool repeat : {true, false}) {
        o.repeat = repeat;
        const Lithology rock(1, o);
        for (const double y : {-1e6, -3.0, 0.0, 2.5, 5.0, 7.25, 1e6}) {
            EXPECT_EQ(rock.hardness({1.0, y, 2.0}), 0.7) << y;
            EXPECT_EQ(rock.bed({1.0, y, 2.0}), 1) << y;
        }
        const Interval h = rock.hardnessBounds({glm::dvec3(-100.0), glm::dvec3(100.0)});
        EXPECT_EQ(h.lo, 0.7);
        EXPECT_EQ(h.hi, 0.7);
        EXPECT_EQ(rock.hardnessLipschitz(), 0.0);
    }
}

TEST(Lithology, DipTiltsTheBedsAndNinetyDegreesStandsThemUp)
{
    LithologyOptions o = threeBeds(0.0);
    o.dip = 0.0;
    o.dipDirection = 37.0;
    const Lithology level(1, o);
    EXPECT_EQ(level.stratigraphicHeight({123.0, 5.5, -77.0}), 5.5); // x and z do not matter

    o.dip = 90.0;
    o.dipDirection = 0.0; // younger beds toward +x, the way they dip
    const Lithology standing(1, o);
    EXPECT_EQ(standing.stratigraphicHeight({5.5, 123.0, -77.0}), 5.5);
    EXPECT_EQ(standing.stratigraphicHeight({5.5, -40.0, 300.0}), 5.5); // y and z do not matter

    o.dip = 30.0;
    o.dipDirection = 90.0; // descending toward +z
    const Lithology tilted(1, o);
    const glm::dvec3 p(4.0, 10.0, 6.0);
    EXPECT_NEAR(tilted.stratigraphicHeight(p), std::cos(M_PI / 6) * 10.0 + std::sin(M_PI / 6) * 6.0, 1e-12);
    // A contact plane dips 30° toward +z: going 1 m toward +z it lies tan 30° m lower.
    const double s = tilted.stratigraphicHeight({0.0, 0.0, 0.0});
    EXPECT_NEAR(tilted.stratigraphicHeight({0.0, -std::tan(M_PI / 6), 1.0}), s, 1e-12);
}

TEST(Lithology, AFaultMovesTheBlockOnOneSide)
{
    LithologyOptions o = threeBeds(0.0);
    o.faultThrow = 10.0;
    o.faultStrike = 90.0; // the trace runs along z; its normal points to −x
    o.faultDip = 90.0;
    o.faultWidth = 1.0;
    const Lithology rock(1, o);
    EXPECT_EQ(rock.stratigraphicHeight({-5.0, 3.0, 40.0}), 13.0);
    EXPECT_EQ(rock.stratigraphicHeight({5.0, 3.0, 40.0}), 3.0);
    EXPECT_NEAR(rock.stratigraphicHeight({0.0, 3.0, 40.0}), 8.0, 1e-12); // halfway, in the fault zone
}

TEST(Lithology, BoundsHoldOverEveryBoxWithFoldsAndFaults)
{
    LithologyOptions o = threeBeds(2.0);
    o.dip = 20.0;
    o.dipDirection = 200.0;
    o.foldAmplitude = 6.0;
    o.foldWavelength = 50.0;
    o.faultThrow = -7.0;
    o.faultPoint = {3.0, 0.0, 5.0};
    o.faultStrike = 30.0;
    o.faultDip = 60.0;
    o.faultWidth = 2.0;
    const Lithology rock(9, o);
    std::uint64_t state = 5;
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        for (int i = 0; i < 400; ++i) {
            glm::dvec3 c, half;
            for (int a = 0; a < 3; ++a) {
                c[a] = origin[a] + uniform(state, -60.0, 60.0);
                half[a] = 0.5 * std::exp(uniform(state, std::log(0.01), std::log(40.0)));
            }
            const WorldBox box{c - half, c + half};
            const Interval s = rock.stratigraphicBounds(box), h = rock.hardnessBounds(box);
            for (int k = 0; k < 40; ++k) {
                glm::dvec3 p;
                for (int a = 0; a < 3; ++a) p[a] = k < 8 ? ((k >> a) & 1 ? box.max[a] : box.min[a]) : uniform(state, box.min[a], box.max[a]);
                const double sp = rock.stratigraphicHeight(p), hp = rock.hardness(p);
                ASSERT_GE(sp, s.lo);
                ASSERT_LE(sp, s.hi);
                ASSERT_GE(hp, h.lo - 1e-12);
                ASSERT_LE(hp, h.hi + 1e-12);
            }
        }
    }
    // And the gradient bound: no jump larger than it allows.
    const double L = rock.hardnessLipschitz();
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 p(uniform(state, -60, 60), uniform(state, -60, 60), uniform(state, -60, 60));
        const glm::dvec3 q = p + glm::dvec3(uniform(state, -0.1, 0.1), uniform(state, -0.1, 0.1), uniform(state, -0.1, 0.1));
        const double dist = std::sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y) + (q.z - p.z) * (q.z - p.z));
        ASSERT_LE(std::abs(rock.hardness(q) - rock.hardness(p)), L * dist * (1.0 + 1e-9) + 1e-12);
    }
}

TEST(Lithology, BadOptionsThrowNamingTheOption)
{
    const auto build = [](const std::function<void(LithologyOptions&)>& change) {
        return [change] {
            LithologyOptions o;
            change(o);
            Lithology rock(1, o);
        };
    };
    expectErrorNaming(build([](LithologyOptions& o) { o.beds.clear(); }), "beds");
    expectErrorNaming(build([](LithologyOptions& o) { o.beds = {{0.0, 0.5}, {0.0, 0.2}}; }), "beds");
    expectErrorNaming(build([](LithologyOptions& o) { o.beds[1].hardness = 1.5; }), "beds[1] hardness");
    expectErrorNaming(build([](LithologyOptions& o) { o.beds[0].thickness = -1.0; }), "beds[0] thickness");
    expectErrorNaming(build([](LithologyOptions& o) { o.beds[0].thickness = NAN; }), "beds[0] thickness");
    expectErrorNaming(build([](LithologyOptions& o) { o.transition = 5.0; }), "transition"); // thinnest bed: 4 m
    expectErrorNaming(build([](LithologyOptions& o) { o.transition = 0.0; }), "transition");
    expectErrorNaming(build([](LithologyOptions& o) { o.dip = 91.0; }), "dip");
    expectErrorNaming(build([](LithologyOptions& o) { o.dipDirection = INFINITY; }), "dip_direction");
    expectErrorNaming(build([](LithologyOptions& o) { o.foldWavelength = 0.0; }), "fold_wavelength");
    expectErrorNaming(build([](LithologyOptions& o) { o.faultWidth = -1.0; }), "fault_width");
    expectErrorNaming(build([](LithologyOptions& o) { o.faultDip = -1.0; }), "fault_dip");
    expectErrorNaming(build([](LithologyOptions& o) { o.datum = NAN; }), "datum");
}
