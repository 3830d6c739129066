// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The [terrain] part of the scene file as a tree of density nodes:
///
///     [terrain]
///     root = "world"                  # the node that is sampled
///
///     [terrain.nodes.world]           # one table per node, named
///     type = "subtract"
///     children = ["land", "tunnels"]  # nodes refer to each other by name
///     smooth = 1.5
///
///     [terrain.nodes.land]
///     type = "heightfield"
///     amplitude = 55.0
///     ...
///
/// Every node type, its keys and defaults come from terrain::NodeRegistry
/// (`strata nodes` prints it). Errors name the file, line, key and value.

#include "TableReader.h"

#include <strata/terrain/DensityField.h>
#include <strata/terrain/LandformMasks.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <strata/scene/Georeference.h>
#include <strata/scene/Scene.h>

namespace strata::scene {

using DensityFieldPtr = std::shared_ptr<const terrain::DensityField>;
using LandformMasksPtr = std::shared_ptr<const terrain::LandformMasks>;
using RockMasksPtr = std::shared_ptr<const terrain::RockMasks>;

/// The node tree built for one seed.
struct TerrainTree
{
    DensityFieldPtr root;
    /// The node whose landform masks layer rules read: the tree's one node
    /// that implements terrain::LandformMasks (an `erode` node), or the one
    /// `[terrain] masks = "NAME"` names when it has several; null when it
    /// has none.
    LandformMasksPtr landformMasks;
    /// The node whose rock masks (hardness, bed) layer rules read: the
    /// tree's one node that implements terrain::RockMasks (a `beds` node),
    /// or the one `[terrain] rock = "NAME"` names; null when it has none.
    RockMasksPtr rockMasks;
    /// The erode nodes' global passes, in the order they were built.
    std::vector<LandformPass> passes;
    /// Where the scene's origin lies on the Earth: from the tree's one
    /// dem_heightfield whose file has a CRS (or the one `[terrain]
    /// georeference = "NAME"` names); empty when it has none.
    std::optional<Georeference> georeference;
};

/// Makes the terrain's tree for a seed (`strata generate --seed` rebuilds
/// it). Each noise node's seed is derived from the scene seed and the
/// node's `seed` key (by default a hash of the node's name). The last tree
/// built is kept: asking again for its seed (the root, then the masks)
/// builds nothing. Thread-safe.
using TerrainBuilder = std::function<TerrainTree(std::uint64_t seed)>;

/// The node type names the scene file accepts, sorted.
const std::vector<std::string>& terrainNodeTypes();

/// Reads [terrain] in its node form (`root`, `masks` and [terrain.nodes.*])
/// and returns a builder for it. The tree is built once here with `seed`
/// (and kept for that seed), so every error surfaces now: unknown node
/// types, keys or child names, cycles, values out of range, NaN or
/// infinite, missing or unreadable heightmap images, a `masks` that names
/// no node with landform masks, several such nodes without `masks`.
/// `inputFiles` (may be null) receives the files read (images, DEMs), sorted.
/// Relative image paths are taken from `baseDirectory` (the scene file's
/// folder). Throws strata::Error "SOURCE:LINE: terrain.nodes.NAME.KEY ...".
/// `terrainTable` must be the reader of [terrain]; its keys are consumed.
/// `maxMemoryBytes` (0: none) refuses, before any work, an erode node whose
/// pass would need more (strata::Error BadInput at its cell_size key).
/// `progress` (may be empty) gets the erode passes' progress during this
/// first build only (SceneLoadOptions::progress); false stops it.
/// `noiseVersion` is the scene's `noise_version`, given to every node's noise.
TerrainBuilder readTerrainNodes(const toml::table* terrainTable, const std::string& source,
                                const std::filesystem::path& baseDirectory, std::uint64_t seed,
                                std::vector<std::filesystem::path>* inputFiles = nullptr,
                                std::uint64_t maxMemoryBytes = 0, const std::function<bool(double)>& progress = {},
                                int noiseVersion = 1);

} // namespace strata::scene
