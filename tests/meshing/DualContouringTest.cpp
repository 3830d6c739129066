// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/Error.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceNets.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <map>

using namespace strata::meshing;

namespace {

// For each of the box's 12 edges, away from the corners: the worst, over
// one-voxel steps along the edge, of the distance from the edge line to
// the nearest mesh vertex within one voxel along it (voxels). Small when the mesh keeps the edge.
double worstEdgeGap(const TriangleMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi, double voxel)
{
    double worst = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const int b = (axis + 1) % 3, c = (axis + 2) % 3;
        for (int corner = 0; corner < 4; ++corner) {
            glm::dvec3 base = lo;
            base[b] = corner & 1 ? hi[b] : lo[b];
            base[c] = corner & 2 ? hi[c] : lo[c];
            for (double s = lo[axis] + 2 * voxel; s <= hi[axis] - 2 * voxel; s += voxel) {
                double best = 1e30;
                for (const glm::vec3& p : mesh.positions) {
                    const glm::dvec3 w = mesh.origin + glm::dvec3(p);
                    if (std::abs(w[axis] - s) > voxel) continue; // a whole cell lies in the window
                    best = std::min(best, std::hypot(w[b] - base[b], w[c] - base[c]));
                }
                worst = std::max(worst, best / voxel);
            }
        }
    }
    return worst;
}

} // namespace

TEST(DualContouring, OneInsideVoxelIsClosed)
{
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(1.0f);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->tree().setValue(openvdb::Coord(0), -0.5f);
    const TriangleMesh mesh = dualContouring(*grid);
    EXPECT_EQ(mesh.vertexCount(), 8u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_TRUE(analyzeTopology(mesh).watertight());
    EXPECT_GT(signedVolume(mesh), 0.0);
}

TEST(DualContouring, ClosedShapesAreWatertightOutwardWithTheRightVolume)
{
    const double voxel = 0.25; // 64 voxels across
    const AnalyticShape shapes[] = {analyticSphere({0.3, -0.2, 0.1}, 8.0),
                                          analyticTorus({0.1, 0.2, -0.3}, 5.5, 2.5),
                                          analyticBox({-7.93, -5.1, -6.37}, {8.04, 5.77, 6.11})};
    for (const auto& shape : shapes) {
        const auto grid = levelSetFromShape(shape, voxel);
        for (int chunk : {0, 32}) {
            DualContouringOptions options;
            options.chunkSize = chunk;
            const TriangleMesh mesh = dualContouring(*grid, options);
            const MeshTopology topology = analyzeTopology(mesh);
            EXPECT_TRUE(topology.watertight()) << "chunk " << chunk << " boundary " << topology.boundaryEdges
                                               << " non-manifold " << topology.nonManifoldEdges;
            EXPECT_NEAR(signedVolume(mesh) / shape.volume, 1.0, 0.01) << "chunk " << chunk;
        }
    }
}

TEST(DualContouring, TunnelCellsStayManifold)
{
    const auto grid = levelSetFromShape(analyticGyroid(6.0, 1.2, 7.0), 0.25);
    DualContouringOptions options;
    options.chunkSize = 16;
    EXPECT_TRUE(analyzeTopology(dualContouring(*grid, options)).watertight());
}

TEST(DualContouring, KeepsTheEdgesOfABox)
{
    // Faces off the voxel lattice, so no edge lies on a grid line.
    const double voxel = 0.25;
    const glm::dvec3 lo(-3.13, -2.41, -2.77), hi(2.94, 2.58, 3.06);
    const auto shape = analyticBox(lo, hi);
    const auto grid = levelSetFromShape(shape, voxel);

    DualContouringOptions fromGrid;
    fromGrid.chunkSize = 16;
    const TriangleMesh mesh = dualContouring(*grid, fromGrid);
    EXPECT_TRUE(analyzeTopology(mesh).watertight());
    const double gridGap = worstEdgeGap(mesh, lo, hi, voxel);
    EXPECT_LT(gridGap, 0.1) << "grid-gradient planes";

    DualContouringOptions exact = fromGrid;
    exact.gradient = shape.gradient;
    const double exactGap = worstEdgeGap(dualContouring(*grid, exact), lo, hi, voxel);
    EXPECT_LT(exactGap, 0.1) << "exact planes";

    // Surface nets rounds the edges off: the measure is meaningful.
    ChunkMeshOptions nets;
    nets.chunkSize = 16;
    EXPECT_GT(worstEdgeGap(surfaceNets(*grid, nets), lo, hi, voxel), 0.2);
}

TEST(DualContouring, AdjacentChunksShareIdenticalBorderVertices)
{
    const auto shape = analyticBox({-3.13, -2.41, -2.77}, {2.94, 2.58, 3.06});
    const auto grid = levelSetFromShape(shape, 0.25);
    DualContouringOptions options;
    options.chunkSize = 8;
    std::map<std::pair<openvdb::Coord, int>, glm::dvec3> firstSeen;
    std::size_t shared = 0;
    for (const openvdb::Coord& c : listChunks(*grid, 8)) {
        const ChunkMesh chunk = dualContouringChunk(*grid, c, options);
        for (std::size_t v = 0; v < chunk.cells.size(); ++v) {
            const glm::dvec3 world = chunk.mesh.origin + glm::dvec3(chunk.mesh.positions[v]);
            const auto [it, inserted] = firstSeen.emplace(std::make_pair(chunk.cells[v], int(chunk.components[v])), world);
            if (!inserted) {
                ++shared;
                EXPECT_EQ(it->second, world);
            }
        }
    }
    EXPECT_GT(shared, 100u);
}

TEST(DualContouring, RejectsBadThreshold)
{
    const auto grid = levelSetFromShape(analyticSphere({0, 0, 0}, 1.0), 0.25);
    DualContouringOptions options;
    options.singularThreshold = 0.0;
    EXPECT_THROW(dualContouring(*grid, options), strata::Error);
    options.singularThreshold = 1.0;
    EXPECT_THROW(dualContouring(*grid, options), strata::Error);
}
