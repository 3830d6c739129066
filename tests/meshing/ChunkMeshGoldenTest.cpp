// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Golden hashes of the chunk meshers' output bytes (positions, normals,
// indices, cells, components) on grids built from integer hashes and square
// roots only (the same floats on every platform): caves and overhangs,
// checkerboard noise (ambiguous and tunnel cells), thin shells (two sheets
// in one cell), tiles next to leaves, chunk borders at negative coordinates,
// far-from-origin, tiny, huge and sheared transforms. Speed work on the
// surface nets and dual contouring paths must keep these bytes; a change of
// the meshes on purpose updates the hashes (the failure prints the new ones).

#include <strata/detail/IntegerHash.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/SurfaceNets.h>

#include <openvdb/math/Maps.h>

#include <gtest/gtest.h>

#include "ByteHash.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

using namespace strata::meshing;

namespace {

struct Hasher : strata::test::ByteHash
{
    void mesh(const TriangleMesh& m)
    {
        vec(m.positions);
        vec(m.normals);
        vec(m.indices);
        bytes(&m.origin, sizeof m.origin);
    }
};

using strata::detail::lowbias32;

float noise(int x, int y, int z)
{
    const std::uint32_t k = lowbias32(std::uint32_t(x) * 73856093u ^ lowbias32(std::uint32_t(y) * 19349663u ^ lowbias32(std::uint32_t(z) * 83492791u)));
    return float(k & 0xffff) / 32768.0f - 1.0f; // [-1, 1), multiples of 2^-15
}

// Terrain with caves and overhangs over [-24, 40)^3, a checkerboard corner
// (every cell ambiguous), a thin spherical shell and an inside tile.
openvdb::FloatGrid::Ptr testGrid(const openvdb::math::Transform::Ptr& transform)
{
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(2.0f);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setTransform(transform);
    openvdb::FloatGrid::Accessor acc = grid->getAccessor();
    for (int x = -24; x < 40; ++x)
        for (int y = -24; y < 40; ++y)
            for (int z = -24; z < 40; ++z) {
                float v;
                if (x >= 24 && y >= 24 && z < -8) {
                    v = ((x + y + z) & 1 ? 0.75f : -0.5f) + 0.25f * noise(x, y, z); // checkerboard
                } else {
                    const float dx = float(x - 2), dy = float(y - 3), dz = float(z - 1);
                    const float r = std::sqrt(dx * dx + dy * dy + dz * dz);
                    const float shell = std::abs(r - 11.5f) - 0.35f; // thinner than a cell
                    const float ground = 0.25f * float(z - 6) + 1.75f * noise(x >> 1, y >> 1, z >> 1) + 0.5f * noise(x, y, z);
                    v = std::min(shell, std::max(ground, -ground - 6.0f)); // ground with caves, an overhang band
                }
                acc.setValue(openvdb::Coord(x, y, z), v);
            }
    // Tiles (no leaf): inside at one 8^3 block, outside next to it.
    grid->tree().addTile(1, openvdb::Coord(40, 0, 0), -1.0f, true);
    grid->tree().addTile(1, openvdb::Coord(40, 8, 0), 1.5f, false);
    return grid;
}

openvdb::math::Transform::Ptr sheared()
{
    openvdb::Mat4d m = openvdb::Mat4d::identity();
    m(0, 0) = 0.5;
    m(1, 0) = 0.125; // shear (dyadic entries: exact)
    m(1, 1) = 0.75;
    m(2, 1) = -0.25;
    m(2, 2) = 1.5;
    m.setTranslation(openvdb::Vec3d(-1024.5, 3.25, 77.0));
    return openvdb::math::Transform::Ptr(new openvdb::math::Transform(openvdb::math::MapBase::Ptr(new openvdb::math::AffineMap(m))));
}

struct Case
{
    const char* name;
    openvdb::math::Transform::Ptr transform;
};

std::vector<Case> cases()
{
    auto scaled = [](double s, const openvdb::Vec3d& t) {
        openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(s);
        xf->postTranslate(t);
        return xf;
    };
    return {{"unit", openvdb::math::Transform::createLinearTransform(1.0)},
            {"far", scaled(0.01, {1e5, -3e4, 7e3})},
            {"tiny", scaled(1e-4, {0.0, 0.0, 0.0})},
            {"huge", scaled(1e3, {-5e5, 0.0, 2.5e6})},
            {"sheared", sheared()}};
}

// Every configuration's hash, folded into one per grid and mesher.
std::uint64_t hashAll(const openvdb::FloatGrid& grid, bool dual)
{
    Hasher all;
    auto gradient = [](const glm::dvec3& w) { return glm::dvec3(0.25 * w.y, -0.5, 1.0 + 0.125 * w.x); };
    struct Config
    {
        NormalMethod normals;
        int chunkSize, projectionSteps;
        double isovalue;
    };
    const Config configs[] = {{NormalMethod::Grid, 32, 0, 0.0},  {NormalMethod::None, 32, 0, 0.0},
                              {NormalMethod::Face, 8, 0, 0.0},   {NormalMethod::Grid, 16, 2, 0.3},
                              {NormalMethod::Gradient, 32, 1, -0.2}, {NormalMethod::Grid, 0, 0, 0.0}};
    for (const Config& c : configs) {
        DualContouringOptions o;
        o.normals = c.normals;
        o.chunkSize = c.chunkSize;
        o.projectionSteps = c.projectionSteps;
        o.isovalue = c.isovalue;
        o.origin = glm::dvec3(3.0, -1.0, 0.5);
        if (c.normals == NormalMethod::Gradient) o.gradient = gradient;
        all.mesh(dual ? dualContouring(grid, o) : surfaceNets(grid, o));
        if (c.chunkSize == 0) continue;
        for (const openvdb::Coord& min : listChunks(grid, c.chunkSize)) {
            const ChunkMesh chunk = dual ? dualContouringChunk(grid, min, o) : surfaceNetsChunk(grid, min, o);
            all.bytes(&chunk.chunkMin, sizeof chunk.chunkMin);
            all.mesh(chunk.mesh);
            all.vec(chunk.cells);
            all.vec(chunk.components);
        }
    }
    return all.h;
}

void expectGolden(bool dual, const std::vector<std::uint64_t>& golden)
{
    const std::vector<Case> all = cases();
    std::string got;
    bool same = golden.size() == all.size();
    for (std::size_t i = 0; i < all.size(); ++i) {
        const std::uint64_t h = hashAll(*testGrid(all[i].transform), dual);
        char text[64];
        std::snprintf(text, sizeof text, "0x%016llxull, ", static_cast<unsigned long long>(h));
        got += text;
        if (i >= golden.size() || golden[i] != h) {
            same = false;
            ADD_FAILURE() << all[i].name << ": mesh bytes changed";
        }
    }
    EXPECT_TRUE(same) << "hashes now: {" << got << "}";
}

} // namespace

TEST(ChunkMeshGolden, SurfaceNetsBytesUnchanged)
{
    expectGolden(false, {0xcd8b745c2757aa28ull, 0x77f6385db276c8d7ull, 0x7c2c12010e47f136ull, 0xffb9ef99eb2cb142ull,
                         0x97e809473d9854e5ull});
}

TEST(ChunkMeshGolden, DualContouringBytesUnchanged)
{
    expectGolden(true, {0x16de904838dda7aaull, 0xb501a426dfde675aull, 0x8108cd244b17ebc4ull, 0xd66dbd6f64b1bcdfull,
                        0x63ba51e743e7f21aull});
}
