// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/Primitives.h>
#include <strata/world/TerrainTile.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <utility>

using namespace strata;
using namespace strata::world;

namespace {

std::shared_ptr<terrain::DensityField> plane(double height)
{
    return std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), height);
}

std::shared_ptr<terrain::DensityField> hills()
{
    terrain::NoiseHeightfieldOptions o;
    o.amplitude = 30.0; // heights within about ±6 m
    o.wavelength = 24.0;
    o.noise.octaves = 3;
    return std::make_shared<terrain::NoiseHeightfield>(7, o);
}

std::shared_ptr<terrain::DensityField> minus(std::shared_ptr<terrain::DensityField> a,
                                             std::shared_ptr<terrain::DensityField> b)
{
    return std::make_shared<terrain::CsgField>(terrain::CsgOperation::SUBTRACT,
                                               std::vector<terrain::DensityFieldPtr>{std::move(a), std::move(b)});
}

std::shared_ptr<terrain::DensityField> plus(std::shared_ptr<terrain::DensityField> a,
                                            std::shared_ptr<terrain::DensityField> b)
{
    return std::make_shared<terrain::CsgField>(terrain::CsgOperation::UNION,
                                               std::vector<terrain::DensityFieldPtr>{std::move(a), std::move(b)});
}

TileBox box(std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t across, std::int64_t up)
{
    TileBox b;
    b.min = {x, y, z};
    b.size = {across, up, across};
    return b;
}

std::size_t countHoles(const TerrainTile& tile)
{
    std::size_t n = 0;
    for (std::uint8_t h : tile.holes) n += h;
    return n;
}

/// Edges used by one triangle only (the mesh's open border).
std::vector<std::pair<std::uint32_t, std::uint32_t>> borderEdges(const meshing::TriangleMesh& mesh)
{
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = mesh.indices[t + e], b = mesh.indices[t + (e + 1) % 3];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const auto& [edge, count] : uses)
        if (count == 1) out.push_back(edge);
    return out;
}

} // namespace

TEST(TerrainTile, FlatGroundIsOneHeightWithoutHolesOrRemainder)
{
    const TerrainTile tile = extractTerrainTile(*plane(3.3), box(-16, -8, -16, 32, 24), {0.5});
    ASSERT_EQ(tile.columns, 33);
    ASSERT_EQ(tile.rows, 33);
    for (double h : tile.heights) EXPECT_NEAR(h, 3.3, 1e-5);
    EXPECT_EQ(countHoles(tile), 0u);
    EXPECT_EQ(tile.columnsAtTop, 0u);
    EXPECT_EQ(tile.columnsAtBottom, 0u);
    EXPECT_GT(tile.surface.indices.size(), 0u);
    // The heightfield draws all of it: nothing left for a mesh.
    EXPECT_EQ(heightfieldRemainder(tile, {}).indices.size(), 0u);
}

TEST(TerrainTile, HeightsAreTheLevelSetsTopCrossing)
{
    // A smooth heightfield: the lattice top lies within a small fraction of
    // a voxel of the true surface (linear interpolation of y − h).
    const auto field = hills();
    const double v = 0.5;
    const TerrainTile tile = extractTerrainTile(*field, box(0, -64, 0, 64, 128), {v});
    EXPECT_EQ(tile.columnsAtTop + tile.columnsAtBottom, 0u);
    const auto& heightfield = static_cast<const terrain::HeightfieldBase&>(*field);
    double worst = 0.0;
    for (int k = 0; k < tile.rows; ++k)
        for (int i = 0; i < tile.columns; ++i)
            worst = std::max(worst, std::abs(tile.height(i, k) - heightfield.height(i * v, k * v)));
    EXPECT_LT(worst, 1e-4) << "the crossing of y − h(x, z) is exact up to float samples";
    EXPECT_EQ(countHoles(tile), 0u);
}

TEST(TerrainTile, NeighboursShareTheirEdgeHeightsBitForBit)
{
    const auto field = hills();
    const TerrainTile a = extractTerrainTile(*field, box(0, -24, 0, 32, 48), {0.5});
    const TerrainTile b = extractTerrainTile(*field, box(32, -24, 0, 32, 48), {0.5});
    const TerrainTile c = extractTerrainTile(*field, box(0, -24, 32, 32, 48), {0.5});
    for (int k = 0; k < a.rows; ++k) EXPECT_EQ(a.height(a.columns - 1, k), b.height(0, k)) << k;
    for (int i = 0; i < a.columns; ++i) EXPECT_EQ(a.height(i, a.rows - 1), c.height(i, 0)) << i;
}

TEST(TerrainTile, CaveMouthIsAHoleAndTheCaveIsMeshedAndWelded)
{
    // Ground at y = 0 with a ball of air breaking through it: a pit into a
    // cave that reaches under the ground on every side.
    const double v = 0.5;
    const auto field = minus(plane(0.0), std::make_shared<terrain::SphereField>(glm::dvec3(8.0, -4.0, 8.0), 5.0));
    const TerrainTile tile = extractTerrainTile(*field, box(0, -24, 0, 32, 32), {v});
    // The mouth's rim (radius 3 around (8, 8)), where the cave reaches under
    // the ground, is cut all round; ground far from it is not, and neither is
    // the middle of the pit: its floor is what a heightfield sees from above.
    int rim = 0, ringCells = 0;
    for (int k = 0; k < tile.rows - 1; ++k)
        for (int i = 0; i < tile.columns - 1; ++i) {
            const double r = std::hypot((i + 0.5) * v - 8.0, (k + 0.5) * v - 8.0);
            if (r > 2.75 && r < 3.25) {
                ++ringCells;
                rim += tile.hole(i, k);
            }
            if (r > 6.0) {
                EXPECT_FALSE(tile.hole(i, k)) << i << "," << k;
            }
        }
    EXPECT_EQ(rim, ringCells) << "every cell on the rim is cut";
    EXPECT_FALSE(tile.hole(int(8.0 / v), int(8.0 / v)));
    EXPECT_FALSE(tile.hole(tile.columns - 2, tile.rows - 2));
    // Columns over the mouth stand on the cave floor.
    EXPECT_NEAR(tile.height(int(8.0 / v), int(8.0 / v)), -9.0, 0.05);

    const meshing::TriangleMesh rest = heightfieldRemainder(tile, {});
    ASSERT_GT(rest.indices.size(), 0u);
    // The cave's ceiling (normals down, under the ground) is in the mesh.
    bool ceiling = false;
    for (std::size_t n = 0; n < rest.positions.size(); ++n)
        ceiling = ceiling || (rest.normals[n].y < -0.5f && rest.origin.y + rest.positions[n].y < -0.5);
    EXPECT_TRUE(ceiling);
    // Weld: the remainder's open border lies on the heightfield outside the
    // holes, within a voxel (the dual mesher's vertices sit inside cells).
    double worst = 0.0;
    for (const auto& [a, b] : borderEdges(rest))
        for (std::uint32_t n : {a, b}) {
            const glm::vec3 p = rest.positions[n];
            worst = std::max(worst, std::abs(rest.origin.y + p.y - heightAt(tile, p.x, p.z)));
        }
    EXPECT_LE(worst, v) << "the cave mesh meets the heightfield within one voxel";
}

TEST(TerrainTile, EnclosedCaveIsMeshedClosedWithoutHoles)
{
    const auto field = minus(plane(0.0), std::make_shared<terrain::SphereField>(glm::dvec3(8.0, -10.0, 8.0), 4.0));
    const TerrainTile tile = extractTerrainTile(*field, box(0, -40, 0, 32, 48), {0.5});
    EXPECT_EQ(countHoles(tile), 0u);
    const meshing::TriangleMesh rest = heightfieldRemainder(tile, {});
    ASSERT_GT(rest.indices.size(), 0u);
    EXPECT_TRUE(borderEdges(rest).empty()) << "a cave under the ground is a closed mesh";
    for (const glm::vec3& p : rest.positions) EXPECT_LT(rest.origin.y + p.y, -5.0);
}

TEST(TerrainTile, FloatingRockLeavesARingOfHolesAndItsUnderside)
{
    // A boulder floating 3 m over the ground: the air under it is open to the
    // sky at its rim, so the rim is cut and the underside meshed.
    const double v = 0.5;
    const auto field = plus(plane(0.0), std::make_shared<terrain::SphereField>(glm::dvec3(8.0, 7.0, 8.0), 4.0));
    const TerrainTile tile = extractTerrainTile(*field, box(0, -8, 0, 32, 32), {v});
    EXPECT_NEAR(tile.height(int(8.0 / v), int(8.0 / v)), 11.0, 0.05);
    EXPECT_GT(countHoles(tile), 0u);
    EXPECT_FALSE(tile.hole(int(8.0 / v), int(8.0 / v))) << "the boulder's top is heightfield";
    EXPECT_FALSE(tile.hole(1, 1));
    const meshing::TriangleMesh rest = heightfieldRemainder(tile, {});
    bool underside = false;
    for (std::size_t n = 0; n < rest.positions.size(); ++n)
        underside = underside || (rest.normals[n].y < -0.9f && rest.origin.y + rest.positions[n].y > 2.5);
    EXPECT_TRUE(underside);
}

TEST(TerrainTile, EngineGridHolesCoverEveryLatticeHole)
{
    const auto field = minus(plane(0.0), std::make_shared<terrain::SphereField>(glm::dvec3(8.0, -4.0, 8.0), 5.0));
    const TerrainTile tile = extractTerrainTile(*field, box(0, -24, 0, 32, 32), {0.5});
    // 32 voxels as 20 engine cells of 0.8 m: every lattice hole is inside a
    // cut engine cell.
    const HeightfieldHoles holes = engineHoles(tile, 20, 20, 0.8);
    for (int k = 0; k < tile.rows - 1; ++k)
        for (int i = 0; i < tile.columns - 1; ++i)
            if (tile.hole(i, k)) {
                const int x = std::min(int((i + 0.5) * 0.5 / 0.8), 19), z = std::min(int((k + 0.5) * 0.5 / 0.8), 19);
                EXPECT_TRUE(holes.cells[std::size_t(z) * 20 + x]) << i << "," << k;
            }
    // The same grid as the lattice gives the lattice's holes.
    EXPECT_EQ(engineHoles(tile, 32, 32, 0.5).cells, tile.holes);
}

TEST(TerrainTile, FarFromTheOriginAndClippedColumns)
{
    // 1e7 m out: heights stay exact to float samples, edges still shared.
    const std::int64_t far = 20000000; // voxels of 0.5 m
    const TerrainTile a = extractTerrainTile(*plane(2.25), box(far, -8, far, 16, 16), {0.5});
    const TerrainTile b = extractTerrainTile(*plane(2.25), box(far + 16, -8, far, 16, 16), {0.5});
    for (double h : a.heights) EXPECT_NEAR(h, 2.25, 1e-5);
    for (int k = 0; k < a.rows; ++k) EXPECT_EQ(a.height(a.columns - 1, k), b.height(0, k));
    // A box below the ground: every column is rock at its top.
    const TerrainTile buried = extractTerrainTile(*plane(100.0), box(0, -8, 0, 8, 8), {0.5});
    EXPECT_EQ(buried.columnsAtTop, std::size_t(81));
    for (double h : buried.heights) EXPECT_EQ(h, 0.0);
    // A box above it: no ground anywhere, every cell a hole.
    const TerrainTile sky = extractTerrainTile(*plane(-100.0), box(0, -8, 0, 8, 8), {0.5});
    EXPECT_EQ(sky.columnsAtBottom, std::size_t(81));
    EXPECT_EQ(countHoles(sky), 64u);
}

TEST(TerrainTile, BadBoxesAreRefused)
{
    const auto field = plane(0.0);
    EXPECT_THROW(extractTerrainTile(*field, box(0, 0, 0, 0, 8), {0.5}), Error);
    EXPECT_THROW(extractTerrainTile(*field, box(0, 0, 0, 2048, 8), {0.5}), Error);
    EXPECT_THROW(extractTerrainTile(*field, box(0, 0, 0, 8, 5000), {0.5}), Error);
    EXPECT_THROW(extractTerrainTile(*field, box(0, 0, 0, 8, 8), {0.0}), Error);
    EXPECT_THROW(extractTerrainTile(*field, box(INT32_MAX - 2, 0, 0, 8, 8), {0.5}), Error);
}
