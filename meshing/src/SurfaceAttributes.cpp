// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/SurfaceAttributes.h>

#include <strata/Error.h>

#include <openvdb/tools/Interpolation.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace strata::meshing {

std::vector<glm::vec2> computeSurfaceAttributes(const openvdb::FloatGrid& grid, const TriangleMesh& mesh,
                                                const SurfaceAttributeOptions& options)
{
    if (mesh.normals.size() != mesh.positions.size()) {
        throw Error(ErrorKind::BadInput, "surface attributes: the mesh needs one normal per vertex");
    }
    if (grid.getGridClass() != openvdb::GRID_LEVEL_SET) {
        throw Error(ErrorKind::BadInput, "surface attributes: grid '" + grid.getName() + "' is not a level set");
    }
    using Accessor = openvdb::FloatGrid::ConstAccessor;
    using Sampler = openvdb::tools::GridSampler<Accessor, openvdb::tools::BoxSampler>;
    const double voxel = grid.voxelSize()[0];
    const double band = double(grid.background());
    const double radius = std::min(options.cavityRadius > 0.0 ? options.cavityRadius : 4.0 * voxel, 0.9 * band);
    const double minStep = 0.5 * voxel;
    const openvdb::Vec3d origin(mesh.origin.x, mesh.origin.y, mesh.origin.z);

    std::vector<glm::vec2> out(mesh.positions.size(), glm::vec2(0.0f));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 2048),
                      [&](const tbb::blocked_range<std::size_t>& range) {
        Accessor accessor = grid.getConstAccessor();
        Sampler sampler(accessor, grid.transform());
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const glm::vec3& p = mesh.positions[i];
            const glm::vec3& n = mesh.normals[i];
            const openvdb::Vec3d w = origin + openvdb::Vec3d(p.x, p.y, p.z);
            const openvdb::Vec3d normal(n.x, n.y, n.z);

            double shortfall = 0.0;
            for (double fraction : {0.25, 0.5, 1.0}) {
                const double d = fraction * radius;
                const double phi = sampler.wsSample(w + normal * d);
                shortfall += std::clamp((d - phi) / d, 0.0, 1.0);
            }
            out[i].x = float(shortfall / 3.0);

            // Sphere-trace straight up from just off the surface: the
            // stored distance never exceeds the true one (the band clamps
            // it), so steps of φ cannot skip rock.
            openvdb::Vec3d q = w + normal * (1.5 * voxel);
            double travelled = 0.0;
            bool covered = false;
            while (travelled < options.coverDistance) {
                const double phi = sampler.wsSample(q);
                if (phi < 0.0) {
                    covered = true;
                    break;
                }
                const double step = std::max(phi, minStep);
                q.y() += step;
                travelled += step;
            }
            out[i].y = covered ? 1.0f : 0.0f;
        }
    });
    return out;
}

} // namespace strata::meshing
