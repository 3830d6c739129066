// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// A DEM file's format recognised by its content and handed to its reader
// (NpyReader, NpzReader, EsriAsciiReader); the checks they share.

#include <strata/terrain/ElevationFile.h>

#include "ElevationFileCommon.h"
#include "EsriAsciiReader.h"
#include "NpyReader.h"
#include "NpzReader.h"

#include <strata/Error.h>

#include <fstream>
#include <iterator>
#include <string>

namespace strata::terrain {

namespace detail {

void failDem(const std::string& name, const std::string& what, int line)
{
    ErrorPlace place;
    place.file = name;
    place.line = line;
    throw Error(ErrorKind::BadInput, name + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what,
                place);
}

std::uint64_t demGridCells(std::uint64_t rows, std::uint64_t columns, const std::string& name)
{
    const std::uint64_t cells = rows * columns;
    if (cells > MAX_DEM_CELLS) {
        failDem(name, std::to_string(rows) + " rows of " + std::to_string(columns) + " values are " +
                          std::to_string(cells) + " cells, more than the " + std::to_string(MAX_DEM_CELLS) +
                          " (16384 x 16384) a DEM may have: crop or resample it");
    }
    return cells;
}

} // namespace detail

using detail::failDem;
using detail::NPY_MAGIC;

ElevationGrid parseElevationFile(std::string_view bytes, const std::string& name)
{
    if (bytes.substr(0, 6) == NPY_MAGIC) return detail::parseNpy(bytes, name);
    if (bytes.substr(0, 4) == std::string_view("PK\x03\x04", 4) ||
        bytes.substr(0, 4) == std::string_view("PK\x05\x06", 4)) {
        return detail::parseNpz(bytes, name);
    }
    if (bytes.empty()) failDem(name, "the file is empty");
    if (bytes.find('\0') != std::string_view::npos) {
        failDem(name, "not a DEM file Strata reads (NumPy .npy, .npz or an ESRI ASCII grid .asc)");
    }
    return detail::parseEsriAscii(bytes, name);
}

ElevationGrid readElevationFile(const std::filesystem::path& path)
{
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) failDem(name, "is a directory, not a DEM file");
    std::ifstream in(path, std::ios::binary);
    if (!in) failDem(name, "cannot open the DEM file");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) failDem(name, "cannot read the DEM file");
    return parseElevationFile(bytes, name);
}

} // namespace strata::terrain
