// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/ProjectToSurface.h>

#include <strata/Error.h>

#include <openvdb/tools/Interpolation.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

namespace strata::meshing {

void projectToSurface(const openvdb::FloatGrid& grid, TriangleMesh& mesh, const ProjectOptions& options)
{
    if (options.steps < 0 || options.steps > 16) {
        throw Error(ErrorKind::BadInput, "projection: steps " + std::to_string(options.steps) + " must be in [0, 16]");
    }
    if (!std::isfinite(options.isovalue) || !(options.maxMoveVoxels >= 0.0)) {
        throw Error(ErrorKind::BadInput, "projection: isovalue must be finite and the largest move non-negative");
    }
    using Accessor = openvdb::FloatGrid::ConstAccessor;
    using Sampler = openvdb::tools::GridSampler<Accessor, openvdb::tools::BoxSampler>;
    const double h = grid.voxelSize()[0];
    const double maxMove = options.maxMoveVoxels * h;
    const openvdb::Vec3d origin(mesh.origin.x, mesh.origin.y, mesh.origin.z);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& range) {
        Accessor accessor = grid.getConstAccessor();
        Sampler sampler(accessor, grid.transform());
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const glm::vec3& q = mesh.positions[i];
            const openvdb::Vec3d start = origin + openvdb::Vec3d(q.x, q.y, q.z);
            openvdb::Vec3d p = start;
            for (int s = 0; s < options.steps; ++s) {
                const double f = sampler.wsSample(p) - options.isovalue;
                const openvdb::Vec3d g(
                    (sampler.wsSample(p + openvdb::Vec3d(h, 0, 0)) - sampler.wsSample(p - openvdb::Vec3d(h, 0, 0))) / (2 * h),
                    (sampler.wsSample(p + openvdb::Vec3d(0, h, 0)) - sampler.wsSample(p - openvdb::Vec3d(0, h, 0))) / (2 * h),
                    (sampler.wsSample(p + openvdb::Vec3d(0, 0, h)) - sampler.wsSample(p - openvdb::Vec3d(0, 0, h))) / (2 * h));
                const double g2 = g.lengthSqr();
                if (!(g2 > 1e-12)) break;
                p -= g * (f / g2);
            }
            openvdb::Vec3d move = p - start;
            const double length = move.length();
            if (!std::isfinite(length)) continue;
            if (length > maxMove) move *= maxMove / length;
            const openvdb::Vec3d local = start + move - origin;
            mesh.positions[i] = glm::vec3(float(local.x()), float(local.y()), float(local.z()));
        }
    });
}

} // namespace strata::meshing
