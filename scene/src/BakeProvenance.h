// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: which machine baked which tile. A worker writes
// provenance/I.json after tile I's record: the host, the CPU architecture
// of the build, the scheduler's job and task, when and how long. It is a
// log, not part of the bake: the tiles, records and manifest are the same
// bytes whoever baked them, and finalizeBake() reports the provenance
// without checking it.

#include <strata/scene/Bake.h>

#include <filesystem>
#include <vector>

namespace strata::scene::detail {

/// The folder of the provenance files, relative to the bake folder.
inline constexpr const char* PROVENANCE_FOLDER = "provenance";

/// Writes `dir`/provenance/`index`.json for this process (atomically).
/// Best effort: a log that cannot be written (a full disk) does not undo
/// a finished tile, so failures are swallowed.
void writeTileProvenance(const std::filesystem::path& dir, int index, double seconds) noexcept;

/// The tiles of `dir` grouped by the host and architecture that baked
/// them, from the provenance files of tiles 0..count−1 (hosts in name
/// order; tiles with no readable file last, as host "unknown", arch "no
/// provenance file", when any tile has one).
std::vector<BakeHostTiles> readProvenance(const std::filesystem::path& dir, int count);

/// The architecture this build runs on: "x86_64", "aarch64", ...
const char* buildArchitecture();

} // namespace strata::scene::detail
