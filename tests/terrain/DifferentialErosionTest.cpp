// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/terrain/DifferentialErosion.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/NodeRegistry.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/Transforms.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

using namespace strata::terrain;

namespace {

/// Hard and soft beds 4 m thick, alternating from y = 0 (hard) up and down.
std::shared_ptr<const Lithology> alternating(double dip = 0.0)
{
    LithologyOptions o;
    o.beds = {{4.0, 1.0}, {4.0, 0.0}};
    o.transition = 0.5;
    o.dip = dip;
    return std::make_shared<Lithology>(1, o);
}

DifferentialErosionOptions retreat(double metres)
{
    DifferentialErosionOptions o;
    o.retreat = metres;
    o.smoothing = 1.0;
    return o;
}

} // namespace

TEST(DifferentialErosion, SoftBedsRetreatFromACliffUnderHardOnes)
{
    // A vertical cliff facing +x across level beds: the soft beds retreat
    // 3 m into it, the hard ones stay, so every hard bed overhangs the
    // soft bed under it.
    const auto cliff = std::make_shared<PlaneField>(glm::dvec3(1.0, 0.0, 0.0), 0.0); // rock at x < 0
    const DifferentialErosionField rock(cliff, alternating(), retreat(3.0));
    EXPECT_GT(rock.density({-2.9, 6.0, 0.0}), 0.0); // the soft bed's alcove
    EXPECT_LT(rock.density({-3.1, 6.0, 0.0}), 0.0);
    EXPECT_LT(rock.density({-0.1, 2.0, 0.0}), 0.0); // the hard bed's face where it was
    EXPECT_GT(rock.density({0.1, 2.0, 0.0}), 0.0);
    EXPECT_NEAR(rock.exposure({-1.0, 6.0, 0.0}), 1.0, 1e-12);

    // Going up the column 1.5 m inside the old face: rock, air (the
    // alcove), rock again (the overhanging hard bed) — twice per period.
    int ceilings = 0;
    bool wasRock = rock.density({-1.5, 0.05, 0.0}) < 0.0;
    for (double y = 0.15; y < 17.0; y += 0.1) {
        const bool isRock = rock.density({-1.5, y, 0.0}) < 0.0;
        ceilings += isRock && !wasRock;
        wasRock = isRock;
    }
    EXPECT_EQ(ceilings, 2);
}

TEST(DifferentialErosion, AFlatTopKeepsItsCapAndTheRockUnderIt)
{
    // Level ground over level beds: the face is parallel to the beds
    // (exposure 0), so nothing changes, not even the soft rock right under
    // a thin hard bed.
    const auto ground = std::make_shared<PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 3.5); // a hard bed's top is at 4
    const DifferentialErosionField rock(ground, alternating(), retreat(5.0));
    for (double y = -12.0; y <= 8.0; y += 0.37) {
        for (const double x : {-7.0, 0.3, 55.0}) {
            ASSERT_EQ(rock.density({x, y, 2.0 * x}), ground->density({x, y, 2.0 * x})) << x << ", " << y;
        }
    }
}

TEST(DifferentialErosion, StandingBedsMakeRidgesOfTheHardOnes)
{
    // Beds dipping 90° under level ground: the soft ones are cut down into
    // trenches between ridges of the hard ones (hogbacks).
    const auto ground = std::make_shared<PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.0);
    const DifferentialErosionField rock(ground, alternating(90.0), retreat(3.0));
    EXPECT_GT(rock.density({6.0, -1.0, 0.0}), 0.0);  // soft bed: air 1 m down
    EXPECT_LT(rock.density({6.0, -3.5, 0.0}), 0.0);  // its trench floor at about −3
    EXPECT_LT(rock.density({2.0, -0.5, 0.0}), 0.0);  // hard bed: rock as before
    EXPECT_GT(rock.density({2.0, 0.5, 0.0}), 0.0);
}

TEST(DifferentialErosion, AFinNarrowerThanTheRetreatOpensIntoAnArch)
{
    // A fin 4 m thick: its soft bed retreats 3 m from each side and is
    // gone, the hard bed above spans the hole.
    const auto fin = std::make_shared<BoxField>(glm::dvec3(0.0, 6.0, 0.0), glm::dvec3(2.0, 6.0, 50.0));
    const DifferentialErosionField rock(fin, alternating(), retreat(3.0));
    EXPECT_GT(rock.density({0.0, 6.0, 0.0}), 0.0);  // the window
    EXPECT_LT(rock.density({0.0, 10.0, 0.0}), 0.0); // the span over it
    EXPECT_LT(rock.density({0.0, 2.0, 0.0}), 0.0);  // the base under it
}

TEST(DifferentialErosion, OnlyRemovesRockAndBoundsHold)
{
    LithologyOptions o;
    o.beds = {{3.0, 0.8}, {5.0, 0.1}, {1.0, 0.5}};
    o.dip = 12.0;
    o.dipDirection = 40.0;
    o.foldAmplitude = 5.0;
    o.foldWavelength = 60.0;
    o.faultThrow = 4.0;
    o.faultStrike = 70.0;
    const auto hills = std::make_shared<WarpField>(std::make_shared<NoiseHeightfield>(3, NoiseHeightfieldOptions{}), 4,
                                                   WarpOptions{});
    const DifferentialErosionField rock(hills, std::make_shared<Lithology>(2, o), retreat(4.0));
    std::uint64_t state = 17;
    const auto uniform = [&state](double lo, double hi) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * double(state >> 11) * 0x1.0p-53;
    };
    for (int i = 0; i < 3000; ++i) {
        const glm::dvec3 p(uniform(-80, 80), uniform(-30, 30), uniform(-80, 80));
        const double d = rock.density(p), c = hills->density(p);
        ASSERT_GE(d, c);
        ASSERT_LE(d, c + 4.0 * (1.0 - 0.1) + 1e-9);
    }
}

TEST(DifferentialErosion, BadOptionsAreNamedInTheLibraryAndTheNode)
{
    const auto ground = std::make_shared<PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.0);
    for (const auto& [key, options] : {std::pair{std::string("retreat"), DifferentialErosionOptions{-1.0, 1.0}},
                                       std::pair{std::string("smoothing"), DifferentialErosionOptions{4.0, 0.0}}}) {
        try {
            DifferentialErosionField rock(ground, alternating(), options);
            ADD_FAILURE() << "no error for " << key;
        } catch (const strata::Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(key + " = ", 0), 0u) << e.what();
        }
    }
    // Through the registry, a check across keys names the key it is about.
    const NodeType* type = NodeRegistry::builtin().find("beds");
    ASSERT_NE(type, nullptr);
    const auto build = [&](const std::string& key, NodeValue value) {
        NodeArgs args("rock", 7);
        for (const NodeKey& k : type->keys) {
            if (k.type == NodeKeyType::Child) args.set(k.name, DensityFieldPtr(ground));
            else if (k.type != NodeKeyType::Seed) args.set(k.name, k.defaultValue);
        }
        args.set(key, std::move(value));
        try {
            type->build(args);
            ADD_FAILURE() << "no error for " << key;
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.place().key, key) << e.what();
        }
    };
    build("transition", NodeValue(5.0)); // thicker than the thinnest bed
    build("beds", NodeValue(std::vector<glm::dvec2>{{4.0, 0.5}, {2.0, 1.5}}));
    build("beds", NodeValue(std::vector<glm::dvec2>{{0.0, 0.5}, {0.0, 0.2}}));
}
