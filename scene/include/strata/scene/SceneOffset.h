// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// `--offset X,Y,Z`: the whole scene moved in the world (large-world
/// checks and far-out chunks): its density field, sampled region and camera.

#include <strata/scene/Scene.h>
#include <strata/scene/Snapshot.h>

#include <glm/vec3.hpp>

namespace strata::scene {

/// The scene moved by `offset` (world metres, finite): the root field (and
/// the `--seed` rebuilder) is wrapped in a terrain::TranslateField, the
/// landform source (and its rebuilder) moved the same way, the
/// region and the scene's explicit camera position and target move with it
/// (the orbit camera follows the moved region by itself). An offset that is
/// a multiple of the voxel size moves the sampled lattice by whole voxels,
/// so the grid's values are the same as at the origin; a multiple of the
/// texture period (1 / material.map_scale) also keeps the snapshot's
/// texturing the same. Throws strata::Error "--offset ..." for a non-finite
/// offset or one above 1e9 m on an axis.
Scene offsetScene(Scene scene, const glm::dvec3& offset);

/// Moves the request's --camera-position and --camera-target by `offset`:
/// with --offset they are given in the scene's own coordinates.
void offsetRequest(SnapshotRequest& request, const glm::dvec3& offset);

} // namespace strata::scene
