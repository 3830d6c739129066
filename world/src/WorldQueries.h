// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the World's queries on the edited density field (the lattice
// samples interpolated trilinearly), independent of the resident chunks:
// density, ray casts and solid boxes. Thread-safe (they read the field and
// the edit layer only).

#include <strata/world/WorldTypes.h>

#include "EditLayer.h"

#include <strata/terrain/DensityField.h>

#include <optional>

namespace strata::world::detail {

/// Trilinear interpolation of the edited lattice samples at `p` (metres).
double latticeDensity(const terrain::DensityField& field, const EditLayer& edits, double voxelSize,
                      const glm::dvec3& p);

/// See World::raycast(); throws strata::Error for a bad ray.
std::optional<RayHit> raycast(const terrain::DensityField& field, const EditLayer& edits, double voxelSize,
                              const glm::dvec3& origin, const glm::dvec3& direction, double maxDistance);

/// See World::isBoxSolid(); throws strata::Error for a bad box.
bool isBoxSolid(const terrain::DensityField& field, const EditLayer& edits, double voxelSize, const glm::dvec3& min,
                const glm::dvec3& max);

} // namespace strata::world::detail
