// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Overhangs counted column by column on fields whose answer is known: a
// ground plane with a floating slab above it (the columns under the slab,
// exactly; none when the depth does not reach the ground under it), a cave
// within the depth (the columns over it) and one deeper (none), a plain
// ground (none), interruption and bad input.

#include <strata/Error.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/OverhangFraction.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/TopSurface.h>

#include "TerrainTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;
using strata::test::errorOf;

DensityFieldPtr ground()
{
    return std::make_shared<PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.0); // rock below y = 0
}

TEST(OverhangFraction, FloatingSlabOverhangsItsColumnsExactly)
{
    // A slab y 5..8 over x, z in −10..10, above the ground: columns at
    // multiples of 4 m from −32 to 32, 17 x 17; under the slab those with
    // |x|, |z| < 10: 5 x 5.
    const CsgField field(CsgOperation::UNION, {ground(), std::make_shared<BoxField>(glm::dvec3(0.0, 6.5, 0.0),
                                                                                    glm::dvec3(10.0, 1.5, 10.0))});
    const TopSurfaceGrid top = sampleTopSurface(field, {{-32.0, -30.0, -32.0}, {32.0, 30.0, 32.0}}, 4.0);
    ASSERT_EQ(top.width, 17);
    ASSERT_EQ(top.height, 17);
    const OverhangStatistics s = measureOverhangs(field, top);
    EXPECT_EQ(s.columns, 289u);
    EXPECT_EQ(s.overhangColumns, 25u);
    EXPECT_EQ(s.fraction, 25.0 / 289.0);
    EXPECT_EQ(s.depth, 20.0);
    EXPECT_EQ(s.step, 0.25);
    EXPECT_EQ(s.samplesPerColumn, 82u);

    // From 5 m below the slab's top (y 3), the ground under it is out of reach.
    OverhangOptions shallow;
    shallow.depth = 5.0;
    EXPECT_EQ(measureOverhangs(field, top, shallow).overhangColumns, 0u);
    // A step that does not divide the depth: the step used does (20 / 7).
    OverhangOptions coarse;
    coarse.step = 3.0;
    const OverhangStatistics c = measureOverhangs(field, top, coarse);
    EXPECT_EQ(c.step, 20.0 / 7.0);
    EXPECT_EQ(c.samplesPerColumn, 9u);
    EXPECT_EQ(c.overhangColumns, 25u); // the gap is 5 m: still seen

    const std::string line = formatOverhangs(s);
    EXPECT_NE(line.find("overhangs "), std::string::npos) << line;
    EXPECT_NE(line.find("8.651 % of 289 columns (25) leave rock more than once within 20 m"), std::string::npos)
        << line;
    EXPECT_NE(line.find("steps of 0.25 m"), std::string::npos) << line;
}

TEST(OverhangFraction, CavesWithinTheDepthCountAndDeeperOnesDoNot)
{
    // A spherical cave of radius 2.5 under columns 1 m apart: the columns
    // with x² + z² < 6.25 pass through it (21 of them: 5 + 2·5 + 2·3).
    const WorldBox region{{-8.0, -40.0, -8.0}, {8.0, 10.0, 8.0}};
    for (const double centre : {-10.0, -30.0}) {
        const CsgField field(CsgOperation::SUBTRACT,
                             {ground(), std::make_shared<SphereField>(glm::dvec3(0.0, centre, 0.0), 2.5)});
        const TopSurfaceGrid top = sampleTopSurface(field, region, 1.0);
        ASSERT_EQ(top.width, 17);
        const OverhangStatistics s = measureOverhangs(field, top);
        EXPECT_EQ(s.overhangColumns, centre == -10.0 ? 21u : 0u) << "cave at y " << centre;
        OverhangOptions deep;
        deep.depth = 35.0;
        EXPECT_EQ(measureOverhangs(field, top, deep).overhangColumns, 21u) << "cave at y " << centre;
    }
    // Plain ground: each column leaves rock once, at the top surface.
    const TopSurfaceGrid flat = sampleTopSurface(*ground(), region, 1.0);
    EXPECT_EQ(measureOverhangs(*ground(), flat).overhangColumns, 0u);
}

TEST(OverhangFraction, ProgressCanInterrupt)
{
    const TopSurfaceGrid top = sampleTopSurface(*ground(), {{-8.0, -30.0, -8.0}, {8.0, 30.0, 8.0}}, 1.0);
    int calls = 0;
    measureOverhangs(*ground(), top, {}, [&calls](double) { return ++calls > 0; });
    EXPECT_GE(calls, 2);
    try {
        measureOverhangs(*ground(), top, {}, [](double fraction) { return fraction < 0.5; });
        ADD_FAILURE() << "not interrupted";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Interrupted);
        EXPECT_NE(std::string(e.what()).find("interrupted"), std::string::npos);
    }
}

TEST(OverhangFraction, BadInputThrows)
{
    const PlaneField field(glm::dvec3(0.0, 1.0, 0.0), 0.0);
    TopSurfaceGrid top;
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top); }).find("0 x 0"), std::string::npos);
    top.width = 2;
    top.height = 2;
    top.cellSize = 1.0;
    top.heights = {0.0, 0.0, NAN, 0.0};
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top); }).find("(x 0, z 1)"), std::string::npos);
    top.heights[2] = 0.0;
    top.cellSize = 0.0;
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top); }).find("cell size"), std::string::npos);
    top.cellSize = 1.0;
    top.heights.pop_back();
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top); }).find("3 heights"), std::string::npos);
    top.heights.push_back(0.0);
    OverhangOptions options;
    options.depth = -1.0;
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top, options); }).find("depth = -1"), std::string::npos);
    options = {};
    options.step = 30.0;
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top, options); }).find("step = 30"), std::string::npos);
    options.step = 1e-6;
    EXPECT_NE(errorOf([&] { measureOverhangs(field, top, options); }).find("larger step"), std::string::npos);
}

} // namespace
