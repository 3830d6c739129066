// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the ErrorPlace of a file, for the mesh readers and writers.

#include <strata/Error.h>

#include <filesystem>

namespace strata::meshing::detail {

/// An ErrorPlace naming `path` (spelled out: `{path.string()}` warns under
/// -Wmissing-field-initializers, since key and value have no initializers).
inline ErrorPlace filePlace(const std::filesystem::path& path)
{
    ErrorPlace place;
    place.file = path.string();
    return place;
}

} // namespace strata::meshing::detail
