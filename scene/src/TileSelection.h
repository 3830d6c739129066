// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the --tiles flag of bake and export-terrain.

#include <string>
#include <vector>

namespace strata::scene::detail {

/// Parses "all" or comma-separated indices and ranges "A-B" into ascending
/// indices below `count`, without repeats. Throws strata::Error (BadInput)
/// naming --tiles, the text and the count.
std::vector<int> parseTileSelection(const std::string& text, int count);

} // namespace strata::scene::detail
