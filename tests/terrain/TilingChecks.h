// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Checks shared by the tests of nodes computed in fixed world blocks
// (erode, erode_detail, talus, scree): a region sampled whole and in
// tiles gives the same voxels in each tile's interior.

#include <strata/terrain/SampleLevelSet.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

namespace strata::test {

/// Sampling of [lo, hi] at 1 m voxels, open on every face (a tile of a
/// larger region).
inline terrain::SampleOptions openBox(const glm::dvec3& lo, const glm::dvec3& hi)
{
    terrain::SampleOptions o;
    o.voxelSize = 1.0;
    o.region = {lo, hi};
    o.closed = false;
    return o;
}

/// Voxels of `where` whose value or active state differs between a and b.
inline std::size_t differences(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b,
                               const openvdb::CoordBBox& where)
{
    std::size_t n = 0;
    auto accA = a.getConstAccessor();
    auto accB = b.getConstAccessor();
    for (auto it = where.begin(); it; ++it) {
        if (accA.getValue(*it) != accB.getValue(*it) || accA.isValueOn(*it) != accB.isValueOn(*it)) ++n;
    }
    return n;
}

/// Samples `field` in tiles × tiles tiles over the x, z square of [lo, hi]
/// and expects every tile's interior (4 voxels in from its sides and from
/// the region's y faces: the band near an open face may differ) to equal
/// `whole`, sampled over [lo, hi] at once. `label` names the run.
inline void expectTilesMatchWhole(const terrain::DensityField& field, const openvdb::FloatGrid& whole,
                                  const glm::dvec3& lo, const glm::dvec3& hi, int tiles, const std::string& label)
{
    constexpr int MARGIN = 4;
    const double step = (hi.x - lo.x) / tiles;
    for (int tz = 0; tz < tiles; ++tz) {
        for (int tx = 0; tx < tiles; ++tx) {
            const glm::dvec3 tileLo(lo.x + tx * step, lo.y, lo.z + tz * step);
            const glm::dvec3 tileHi(tileLo.x + step, hi.y, tileLo.z + step);
            const auto tile = terrain::sampleLevelSet(field, openBox(tileLo, tileHi));
            const openvdb::Coord a(int(tileLo.x) + MARGIN, int(lo.y) + MARGIN, int(tileLo.z) + MARGIN);
            const openvdb::Coord b(int(tileHi.x) - MARGIN, int(hi.y) - MARGIN, int(tileHi.z) - MARGIN);
            EXPECT_EQ(differences(whole, *tile, openvdb::CoordBBox(a, b)), 0u)
                << label << ": " << tiles << "x" << tiles << " tile " << tx << "," << tz;
        }
    }
}

} // namespace strata::test
