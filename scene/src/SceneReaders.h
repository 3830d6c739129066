// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The readers of the scene file's tables, shared by Scene.cpp (internal to
/// strata::scene: they take the TOML reader, which is not part of the API).

#include "TableReader.h"

#include <strata/scene/Quality.h>
#include <strata/scene/SceneMaterial.h>

#include <filesystem>

namespace strata::scene {

/// Reads [quality] from the scene's root table; throws strata::Error
/// "SOURCE:LINE: quality.KEY ..." for unknown keys, wrong types, values
/// out of range and unknown presets.
QualityTable readQuality(TableReader& root);

/// Reads [material] (and [materials.*]) from the scene's root table.
/// `baseDir` resolves relative file names. Throws strata::Error
/// "SOURCE:LINE: material.KEY ..." for unknown keys, wrong types,
/// out-of-range values and unknown built-in sets; also for a map file that
/// is missing ("... no such file"), for a layer band on the landform
/// masks (flow, wear, deposition, water) when `landformSource` is false
/// (the terrain has no `erode` node), and for one on the rock masks
/// (hardness, bed) when `rockSource` is false (no `beds` node).
void readMaterial(TableReader& root, MaterialSettings& settings, const std::filesystem::path& baseDir,
                  bool landformSource, bool rockSource);

} // namespace strata::scene
