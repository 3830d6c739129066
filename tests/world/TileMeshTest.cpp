// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// world::meshTile(): tiles clipped exactly to their boxes weld into one
// closed surface, skirts hang from faces with a neighbour, and bad boxes
// are refused.

#include <strata/world/TileMesh.h>

#include <strata/Error.h>
#include <strata/terrain/DensityField.h>
#include <strata/terrain/Primitives.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <tuple>
#include <vector>

using namespace strata;
using namespace strata::world;

namespace {

using Key = std::array<double, 3>;

/// Triangles of several tile meshes in world metres, welded by exact position.
struct Welded
{
    std::map<Key, std::uint32_t> index;
    std::vector<Key> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;

    void add(const meshing::TriangleMesh& mesh)
    {
        std::vector<std::uint32_t> local;
        for (const glm::vec3& p : mesh.positions) {
            const Key key{mesh.origin.x + double(p.x), mesh.origin.y + double(p.y), mesh.origin.z + double(p.z)};
            const auto [it, added] = index.emplace(key, std::uint32_t(positions.size()));
            if (added) positions.push_back(key);
            local.push_back(it->second);
        }
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            triangles.push_back({local[mesh.indices[t]], local[mesh.indices[t + 1]], local[mesh.indices[t + 2]]});
    }

    /// Undirected edges used by exactly one triangle.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> boundaryEdges() const
    {
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const auto& t : triangles)
            for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
        std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
        for (const auto& [edge, count] : uses)
            if (count == 1) out.push_back(edge);
        return out;
    }
};

TileBox box(std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t size, unsigned faces = 0)
{
    TileBox b;
    b.min = {x, y, z};
    b.size = {size, size, size};
    b.neighbourFaces = faces;
    return b;
}

} // namespace

TEST(TileMesh, EightTilesThroughASphereWeldIntoAClosedSurface)
{
    // A sphere centred on a tile corner: every tile holds an eighth of it.
    const terrain::SphereField sphere(glm::dvec3(0.3, -0.2, 0.1), 5.3);
    for (int level : {0, 1, 2}) {
        Welded welded;
        for (int x : {-16, 0})
            for (int y : {-16, 0})
                for (int z : {-16, 0}) {
                    TileMeshOptions options;
                    options.voxelSize = 0.5;
                    options.level = level;
                    const TileMeshData tile = meshTile(sphere, box(x, y, z, 16), options);
                    ASSERT_GT(tile.surface.triangleCount(), 0u);
                    EXPECT_EQ(tile.skirt.triangleCount(), 0u) << "no neighbour faces: no skirt";
                    // Every vertex inside its own box (closed), in metres.
                    for (const glm::vec3& p : tile.surface.positions)
                        for (int a = 0; a < 3; ++a) {
                            EXPECT_GE(p[a], 0.0f);
                            EXPECT_LE(p[a], 8.0f);
                        }
                    welded.add(tile.surface);
                }
        EXPECT_TRUE(welded.boundaryEdges().empty())
            << "level " << level << ": " << welded.boundaryEdges().size() << " boundary edges: the cuts differ";
    }
}

TEST(TileMesh, AdjacentTilesShareTheirCutExactlyAndFarFromTheOrigin)
{
    // A sloping plane through two tiles side by side, 1e6 m from the origin.
    const double far = 1048576.0; // a power of two: world positions stay exact
    const terrain::PlaneField plane(glm::normalize(glm::dvec3(0.3, 1.0, 0.2)), -0.37);
    struct Shifted final : terrain::DensityField
    {
        const terrain::DensityField& base;
        glm::dvec3 shift;
        Shifted(const terrain::DensityField& b, glm::dvec3 s) : base(b), shift(s) {}
        double density(const glm::dvec3& p) const override { return base.density(p - shift); }
        double lipschitz() const override { return 1.0; }
        double distanceBound(const glm::dvec3& p) const override { return base.distanceBound(p - shift); }
    } field(plane, glm::dvec3(far, 0.0, far));
    const auto voxel = std::int64_t(far); // voxel size 1 m
    TileMeshOptions options;
    options.voxelSize = 1.0;
    const TileMeshData a = meshTile(field, box(voxel - 32, -16, voxel - 16, 32), options);
    const TileMeshData b = meshTile(field, box(voxel, -16, voxel - 16, 32), options);
    Welded welded;
    welded.add(a.surface);
    welded.add(b.surface);
    // The union is one patch: its boundary lies only on the union box's outer faces.
    for (const auto& [i, j] : welded.boundaryEdges()) {
        const Key& p = welded.positions[i];
        const Key& q = welded.positions[j];
        const bool onSeam = p[0] == far && q[0] == far;
        EXPECT_FALSE(onSeam) << "a boundary edge on the shared face x = " << far << " at z " << p[2];
    }
    std::size_t onFace = 0;
    for (const Key& p : welded.positions) onFace += p[0] == far;
    EXPECT_GT(onFace, 10u) << "the plane crosses the shared face";
}

TEST(TileMesh, SkirtsHangFromFacesWithANeighbourIntoTheRock)
{
    const terrain::PlaneField ground(glm::dvec3(0.0, 1.0, 0.0), 0.3); // a flat ground
    TileMeshOptions options;
    options.voxelSize = 0.5;
    options.skirtDepth = 2.0;
    const unsigned maxX = 1u << 1;
    const TileMeshData tile = meshTile(ground, box(0, -16, 0, 32, maxX), options);
    ASSERT_GT(tile.skirt.triangleCount(), 0u);
    const float faceX = 16.0f; // the tile's maximum x face, metres from its corner
    float top = -1e9f, bottom = 1e9f;
    for (const glm::vec3& p : tile.skirt.positions) {
        EXPECT_EQ(p.x, faceX) << "a skirt lies in its face plane";
        top = std::max(top, p.y);
        bottom = std::min(bottom, p.y);
    }
    // The surface is flat: the skirt spans 2 m from it, into the rock.
    const double surfaceY = tile.surface.positions.front().y;
    EXPECT_NEAR(top - bottom, 2.0, 1e-5);
    EXPECT_NEAR(top, surfaceY, 1e-5);
    const double deep = std::abs(top - surfaceY) < 1e-5 ? bottom : top;
    EXPECT_LT(ground.density(tile.skirt.origin + glm::dvec3(faceX, deep, 8.0)), 0.0)
        << "the skirt's far edge is in the rock";
}

TEST(TileMesh, SkirtsStayInsideTheBoxAndOffFacesWithoutANeighbour)
{
    // A slope whose skirts on the x faces lean toward −z (away from the
    // air, within the face plane): near z = 0 they would leave the box
    // through a face with no neighbour (the world's side here).
    const terrain::PlaneField slope(glm::normalize(glm::dvec3(-0.4, 1.0, 0.5)), 0.2);
    TileMeshOptions options;
    options.voxelSize = 0.5;
    options.skirtDepth = 3.0;
    const unsigned xFaces = 1u | 2u;
    const TileMeshData tile = meshTile(slope, box(0, -16, 0, 16, xFaces), options);
    ASSERT_GT(tile.skirt.triangleCount(), 0u);
    for (const glm::vec3& p : tile.skirt.positions) {
        EXPECT_TRUE(p.x == 0.0f || p.x == 8.0f) << "a skirt off the faces with a neighbour, x " << p.x;
        for (int a = 0; a < 3; ++a) {
            EXPECT_GE(p[a], 0.0f) << "axis " << a;
            EXPECT_LE(p[a], 8.0f) << "axis " << a;
        }
    }
    // Every skirt triangle has an area (none collapsed by the clamp).
    const meshing::TriangleMesh& s = tile.skirt;
    for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
        const glm::vec3 a = s.positions[s.indices[t]], b = s.positions[s.indices[t + 1]], c = s.positions[s.indices[t + 2]];
        EXPECT_GT(glm::length(glm::cross(b - a, c - a)), 0.0f);
    }
}

TEST(TileMesh, NoSkirtWhereTheSurfaceLiesNearlyInTheFacePlane)
{
    // A slab cut (the box's top face) through ground tilted 10°: a skirt
    // there would lie in the cut plane, above the ground beyond a bump, and
    // both slabs would make it. Tilted 45°, the cut needs its skirt.
    const unsigned top = 1u << 3, side = 1u << 1;
    TileMeshOptions options;
    options.voxelSize = 0.5;
    options.skirtDepth = 2.0;
    // Ground tilted about z through (x0, y0, 0): through the top face y = 4 m
    // at x = 6 m, or through the side face x = 8 m at y = 0.
    for (const auto& [degrees, faces, x0, y0, made] :
         {std::tuple{10.0, top, 6.0, 4.0, false}, std::tuple{45.0, top, 6.0, 4.0, true},
          std::tuple{80.0, side, 8.0, 0.0, false}, std::tuple{45.0, side, 8.0, 0.0, true}}) {
        const double r = glm::radians(degrees);
        const glm::dvec3 normal(-std::sin(r), std::cos(r), 0.0);
        const terrain::PlaneField ground(normal, glm::dot(normal, glm::dvec3(x0, y0, 0.0))); // n·p − offset
        const TileMeshData tile = meshTile(ground, box(0, -8, 0, 16, faces), options);
        ASSERT_GT(tile.surface.triangleCount(), 0u);
        EXPECT_EQ(tile.skirt.triangleCount() > 0, made) << "ground tilted " << degrees << "°, faces " << faces;
    }
}

TEST(TileMesh, SkirtsEndWhereTheyWouldLeaveTheRockIntoACave)
{
    // Flat ground with a cave 0.5 m under it at the tile's side: a 3 m skirt
    // hanging from the side would show in the cave; it ends at the cave's roof.
    struct GroundOverCave final : terrain::DensityField
    {
        glm::dvec3 centre{8.0, -2.0, 4.0};
        double radius = 1.5;
        double density(const glm::dvec3& p) const override
        {
            return std::max(p.y, radius - glm::length(p - centre)); // air positive
        }
        double lipschitz() const override { return 1.0; }
        double distanceBound(const glm::dvec3& p) const override { return density(p); }
    } field;
    TileMeshOptions options;
    options.voxelSize = 0.5;
    options.skirtDepth = 3.0;
    const TileMeshData tile = meshTile(field, box(0, -8, 0, 16, 1u << 1), options);
    const meshing::TriangleMesh& s = tile.skirt;
    ASSERT_GT(s.triangleCount(), 0u);
    float deepest = 0.0f;
    std::size_t inAir = 0;
    for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = s.origin + glm::dvec3(s.positions[s.indices[t + k]]);
        for (int k = 0; k < 3; ++k)
            if (std::abs(p[k].z - field.centre.z) > field.radius + 0.1) deepest = std::min(deepest, float(p[k].y));
        inAir += field.density((p[0] + p[1] + p[2]) / 3.0) > 0.02;
    }
    EXPECT_EQ(inAir, 0u) << "skirt triangles in the cave";
    EXPECT_NEAR(deepest, -3.0f, 0.05f) << "beside the cave the ground's skirt keeps its depth";
}

TEST(TileMesh, RefusesBoxesOffTheLevelsLattice)
{
    const terrain::SphereField sphere(glm::dvec3(0.0), 3.0);
    TileMeshOptions options;
    options.level = 2;
    EXPECT_THROW(meshTile(sphere, box(2, 0, 0, 16), options), Error) << "min not a multiple of 4 voxels";
    EXPECT_THROW(meshTile(sphere, box(0, 0, 0, 18), options), Error) << "size not a multiple of 4 voxels";
    options.level = 0;
    EXPECT_THROW(meshTile(sphere, box(0, 0, 0, 2048), options), Error) << "more than 1024 cells";
    EXPECT_THROW(meshTile(sphere, box(0, 0, 0, 0), options), Error) << "empty";
    options.voxelSize = 0.0;
    EXPECT_THROW(meshTile(sphere, box(0, 0, 0, 16), options), Error) << "voxel size 0";
}
