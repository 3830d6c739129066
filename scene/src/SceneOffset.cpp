// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/SceneOffset.h>

#include <strata/Error.h>
#include <strata/terrain/Transforms.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

namespace strata::scene {

namespace {

/// Landform masks moved by `offset`, as TranslateField moves the field:
/// masks(x, z) = source(x − offset.x, z − offset.z).
class OffsetLandformMasks final : public terrain::LandformMasks
{
public:
    OffsetLandformMasks(std::shared_ptr<const terrain::LandformMasks> source, const glm::dvec3& offset)
        : mSource(std::move(source)), mOffset(offset)
    {
    }

    void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const override
    {
        std::vector<double> sx(n), sz(n);
        for (std::size_t i = 0; i < n; ++i) {
            sx[i] = x[i] - mOffset.x;
            sz[i] = z[i] - mOffset.z;
        }
        mSource->landformMasks(sx.data(), sz.data(), n, out);
    }

private:
    std::shared_ptr<const terrain::LandformMasks> mSource;
    glm::dvec3 mOffset;
};

/// Rock masks moved by `offset`: masks(p) = source(p − offset).
class OffsetRockMasks final : public terrain::RockMasks
{
public:
    OffsetRockMasks(std::shared_ptr<const terrain::RockMasks> source, const glm::dvec3& offset)
        : mSource(std::move(source)), mOffset(offset)
    {
    }

    void rockMasks(const double* x, const double* y, const double* z, std::size_t n, glm::vec2* out) const override
    {
        std::vector<double> sx(n), sy(n), sz(n);
        for (std::size_t i = 0; i < n; ++i) {
            sx[i] = x[i] - mOffset.x;
            sy[i] = y[i] - mOffset.y;
            sz[i] = z[i] - mOffset.z;
        }
        mSource->rockMasks(sx.data(), sy.data(), sz.data(), n, out);
    }

private:
    std::shared_ptr<const terrain::RockMasks> mSource;
    glm::dvec3 mOffset;
};

/// `source` (a mask source, or its rebuilder for another seed) moved by
/// `offset` through the wrapper `Offset`.
template<typename Offset, typename Masks>
std::shared_ptr<const Masks> offsetMasks(std::shared_ptr<const Masks> source, const glm::dvec3& offset)
{
    if (!source) return source;
    return std::make_shared<Offset>(std::move(source), offset);
}

template<typename Offset, typename Masks>
std::function<std::shared_ptr<const Masks>(std::uint64_t)>
offsetMasks(std::function<std::shared_ptr<const Masks>(std::uint64_t)> build, const glm::dvec3& offset)
{
    if (!build) return build;
    return [build = std::move(build), offset](std::uint64_t seed) {
        return offsetMasks<Offset, Masks>(build(seed), offset);
    };
}

} // namespace

Scene offsetScene(Scene scene, const glm::dvec3& offset)
{
    for (int axis = 0; axis < 3; ++axis) {
        if (!std::isfinite(offset[axis]) || std::abs(offset[axis]) > 1e9) {
            std::ostringstream text;
            text << "--offset '" << offset.x << "," << offset.y << "," << offset.z
                 << "' is out of range (finite, |value| <= 1e9 metres)";
            throw Error(ErrorKind::BadInput, text.str());
        }
    }
    if (offset == glm::dvec3(0.0)) return scene;
    // The sampler indexes voxels with 32-bit coordinates (at most 2^30 voxels
    // from the origin): refuse an offset that moves the region past that now,
    // naming the flag, rather than in the sampler.
    const double reach = scene.voxelSize * double(1 << 30);
    for (int axis = 0; axis < 3; ++axis) {
        const double far = std::max(std::abs(scene.region.min[axis] + offset[axis]),
                                    std::abs(scene.region.max[axis] + offset[axis]));
        if (!(far < reach)) {
            std::ostringstream text;
            text << "--offset '" << offset.x << "," << offset.y << "," << offset.z
                 << "' moves the region beyond what voxel_size = " << scene.voxelSize
                 << " can sample (|coordinate| < " << reach << " m)";
            throw Error(ErrorKind::BadInput, text.str(), {"", 0, "--offset", ""});
        }
    }
    if (scene.field) scene.field = std::make_shared<terrain::TranslateField>(scene.field, offset);
    if (scene.buildField) {
        scene.buildField = [build = scene.buildField, offset](std::uint64_t seed) -> terrain::DensityFieldPtr {
            return std::make_shared<terrain::TranslateField>(build(seed), offset);
        };
    }
    scene.landformMasks = offsetMasks<OffsetLandformMasks>(scene.landformMasks, offset);
    scene.buildLandformMasks = offsetMasks<OffsetLandformMasks>(scene.buildLandformMasks, offset);
    scene.rockMasks = offsetMasks<OffsetRockMasks>(scene.rockMasks, offset);
    scene.buildRockMasks = offsetMasks<OffsetRockMasks>(scene.buildRockMasks, offset);
    scene.region.min += offset;
    scene.region.max += offset;
    if (scene.camera.position) *scene.camera.position += offset;
    if (scene.camera.target) *scene.camera.target += offset;
    // The fog's base height is world metres: it moves with the terrain.
    scene.lighting.atmosphere.fogBaseHeight += offset.y;
    return scene;
}

void offsetRequest(SnapshotRequest& request, const glm::dvec3& offset)
{
    if (request.cameraPosition) *request.cameraPosition += offset;
    if (request.cameraTarget) *request.cameraTarget += offset;
}

} // namespace strata::scene
