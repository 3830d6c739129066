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

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace strata::scene {

using DensityFieldPtr = std::shared_ptr<const terrain::DensityField>;

/// Makes the terrain's root field for a seed (`strata generate --seed`
/// rebuilds it). Each noise node's seed is derived from the scene seed and
/// the node's `seed` key (by default a hash of the node's name).
using TerrainBuilder = std::function<DensityFieldPtr(std::uint64_t seed)>;

/// The node type names the scene file accepts, sorted.
const std::vector<std::string>& terrainNodeTypes();

/// Reads [terrain] in its node form (`root` and [terrain.nodes.*]) and
/// returns a builder for it. The tree is built once here with `seed`, so every
/// error surfaces now: unknown node types, keys or child names, cycles, values
/// out of range, NaN or infinite, missing or unreadable heightmap images.
/// `inputFiles` (may be null) receives the image files read, sorted.
/// Relative image paths are taken from `baseDirectory` (the scene file's
/// folder). Throws strata::Error "SOURCE:LINE: terrain.nodes.NAME.KEY ...".
/// `terrainTable` must be the reader of [terrain]; its keys are consumed.
TerrainBuilder readTerrainNodes(const toml::table* terrainTable, const std::string& source,
                                const std::filesystem::path& baseDirectory, std::uint64_t seed,
                                std::vector<std::filesystem::path>* inputFiles = nullptr);

} // namespace strata::scene
