// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Queries of strata::world::World that never wait for meshes: ray casts,
// density, solid boxes.

#include <strata/Error.h>
#include <strata/terrain/Primitives.h>
#include <strata/world/World.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace strata::test {
namespace {

using world::EditShape;
using world::World;
using world::WorldOptions;

WorldOptions queryOptions()
{
    WorldOptions o;
    o.voxelSize = 0.5;
    o.chunkSize = 16;
    o.levels = 2;
    o.lodDistance = 28.0;
    o.threads = 1;
    return o;
}

const glm::dvec3 CENTRE(0.37, -0.21, 0.13);
constexpr double RADIUS = 20.0;

TEST(WorldQuery, RayCastsHitTheSphereWithinHalfAVoxel)
{
    World w(std::make_shared<terrain::SphereField>(CENTRE, RADIUS), queryOptions());
    int hits = 0;
    for (int i = 0; i < 64; ++i) {
        // Deterministic directions over the sphere (golden spiral), rays from 60 m out.
        const double z = 1.0 - (i + 0.5) / 32.0;
        const double r = std::sqrt(1.0 - z * z), phi = i * 2.399963229728653;
        const glm::dvec3 dir(r * std::cos(phi), r * std::sin(phi), z);
        const glm::dvec3 origin = CENTRE + 60.0 * dir + glm::dvec3(0.1, 0.05, -0.07);
        const std::optional<world::RayHit> hit = w.raycast(origin, -dir * 3.0, 100.0);
        ASSERT_TRUE(hit);
        ++hits;
        EXPECT_NEAR(glm::length(hit->position - CENTRE), RADIUS, 0.25); // half a voxel
        EXPECT_NEAR(hit->distance, glm::length(hit->position - origin), 1e-9);
        EXPECT_GT(glm::dot(hit->normal, glm::normalize(hit->position - CENTRE)), 0.99);
        EXPECT_NEAR(w.density(hit->position), 0.0, 1e-6);
    }
    EXPECT_EQ(hits, 64);
    // Misses: too short, pointing away, passing by.
    EXPECT_FALSE(w.raycast(CENTRE + glm::dvec3(60, 0, 0), glm::dvec3(-1, 0, 0), 39.0));
    EXPECT_FALSE(w.raycast(CENTRE + glm::dvec3(60, 0, 0), glm::dvec3(1, 0, 0), 500.0));
    EXPECT_FALSE(w.raycast(CENTRE + glm::dvec3(60, 21, 0), glm::dvec3(-1, 0, 0), 500.0));
    // From inside: a hit at once.
    const auto inside = w.raycast(CENTRE, glm::dvec3(0, 1, 0), 10.0);
    ASSERT_TRUE(inside);
    EXPECT_EQ(inside->distance, 0.0);
    EXPECT_THROW(w.raycast(CENTRE, glm::dvec3(0.0), 10.0), Error);
    EXPECT_THROW(w.raycast(CENTRE, glm::dvec3(1, 0, 0), -1.0), Error);
}

TEST(WorldQuery, RayCastsSeeEditsWithoutMeshes)
{
    World w(std::make_shared<terrain::SphereField>(CENTRE, RADIUS), queryOptions());
    const glm::dvec3 top = CENTRE + glm::dvec3(0.0, RADIUS, 0.0);
    // Dig a 4 m hole at the top: a ray straight down now hits its bottom.
    w.dig(EditShape::sphere(top, 4.0));
    const auto hit = w.raycast(top + glm::dvec3(0.0, 30.0, 0.0), glm::dvec3(0, -1, 0), 100.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->position.y, top.y - 4.0, 0.25);
    EXPECT_GT(hit->normal.y, 0.95);
    // Fill a block floating above: the ray stops on its top face.
    w.fill(EditShape::box(top + glm::dvec3(0.0, 10.0, 0.0), glm::dvec3(2.0)));
    const auto block = w.raycast(top + glm::dvec3(0.0, 30.0, 0.0), glm::dvec3(0, -1, 0), 100.0);
    ASSERT_TRUE(block);
    EXPECT_NEAR(block->position.y, top.y + 12.0, 0.25);
}

TEST(WorldQuery, DensityInterpolatesTheLattice)
{
    World w(std::make_shared<terrain::SphereField>(CENTRE, RADIUS), queryOptions());
    // On lattice points: the field itself.
    EXPECT_NEAR(w.density(glm::dvec3(1.0, 2.5, -3.0)), glm::length(glm::dvec3(1.0, 2.5, -3.0) - CENTRE) - RADIUS, 1e-5);
    // Between them: within the interpolation error of a sphere's distance.
    for (double x = -30.0; x <= 30.0; x += 3.7) {
        const glm::dvec3 p(x, 0.3 * x, -0.2 * x + 1.1);
        EXPECT_NEAR(w.density(p), glm::length(p - CENTRE) - RADIUS, 0.05);
    }
}

TEST(WorldQuery, BoxSolid)
{
    World w(std::make_shared<terrain::SphereField>(CENTRE, RADIUS), queryOptions());
    EXPECT_TRUE(w.isBoxSolid(CENTRE - 5.0, CENTRE + 5.0));
    EXPECT_TRUE(w.isBoxSolid(CENTRE - 11.0, CENTRE + 11.0)); // corners 19.05 m out: many whole blocks
    EXPECT_FALSE(w.isBoxSolid(CENTRE - 12.0, CENTRE + 12.0)); // corners 20.8 m out
    EXPECT_FALSE(w.isBoxSolid(CENTRE + glm::dvec3(19.0, -1, -1), CENTRE + glm::dvec3(21.0, 1, 1)));
    EXPECT_FALSE(w.isBoxSolid(CENTRE + 30.0, CENTRE + 40.0));
    EXPECT_TRUE(w.isBoxSolid(CENTRE + 2.0, CENTRE + 2.0)); // a point
    // A small hole inside the box makes it not solid; filling it back does.
    w.dig(EditShape::sphere(CENTRE + glm::dvec3(3.0, 1.0, -2.0), 0.6));
    EXPECT_FALSE(w.isBoxSolid(CENTRE - 5.0, CENTRE + 5.0));
    EXPECT_TRUE(w.isBoxSolid(CENTRE - glm::dvec3(5.0), CENTRE + glm::dvec3(1.0, 5.0, 5.0)));
    w.fill(EditShape::sphere(CENTRE + glm::dvec3(3.0, 1.0, -2.0), 0.6));
    EXPECT_TRUE(w.isBoxSolid(CENTRE - 5.0, CENTRE + 5.0));
    EXPECT_THROW(w.isBoxSolid(CENTRE + 1.0, CENTRE), Error);
}

} // namespace
} // namespace strata::test
