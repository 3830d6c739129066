// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "EsriAsciiReader.h"

#include "ElevationFileCommon.h"

#include <strata/Format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace strata::terrain::detail {

namespace {

/// Splits text into whitespace-separated tokens, counting lines.
class Tokens
{
public:
    explicit Tokens(std::string_view text) : mText(text) {}

    /// The next token (empty at the end); `line` receives its line.
    std::string_view next(int& line)
    {
        while (mPos < mText.size() && isSpace(mText[mPos])) {
            if (mText[mPos] == '\n') ++mLine;
            ++mPos;
        }
        const std::size_t start = mPos;
        while (mPos < mText.size() && !isSpace(mText[mPos])) ++mPos;
        line = mLine;
        return mText.substr(start, mPos - start);
    }
    /// Looks at the next token without taking it.
    std::string_view peek(int& line)
    {
        const std::size_t pos = mPos;
        const int lines = mLine;
        const std::string_view token = next(line);
        mPos = pos;
        mLine = lines;
        return token;
    }
    std::size_t remaining() const { return mText.size() - mPos; }

private:
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

    std::string_view mText;
    std::size_t mPos = 0;
    int mLine = 1;
};

std::string lower(std::string_view text)
{
    std::string out(text);
    for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string shown(std::string_view token)
{
    std::string out;
    for (char c : token.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return out + (token.size() > 40 ? "..." : "");
}

std::optional<double> toNumber(std::string_view token)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
    return value;
}

bool startsNumber(std::string_view token)
{
    const char c = token.empty() ? '\0' : token.front();
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
}

} // namespace

ElevationGrid parseEsriAscii(std::string_view text, const std::string& name)
{
    Tokens tokens(text);
    struct Field
    {
        double value = 0.0;
        int line = 0;
        bool set = false;
    };
    const std::vector<std::string> keys = {"ncols",     "nrows",    "xllcorner", "yllcorner", "xllcenter",
                                           "yllcenter", "cellsize", "dx",        "dy",        "nodata_value"};
    std::vector<Field> fields(keys.size());
    auto field = [&](const char* key) -> Field& {
        return fields[std::size_t(std::find(keys.begin(), keys.end(), key) - keys.begin())];
    };
    int line = 0;
    for (;;) {
        const std::string_view token = tokens.peek(line);
        if (token.empty() || startsNumber(token)) break;
        tokens.next(line);
        const std::string key = lower(token);
        const auto found = std::find(keys.begin(), keys.end(), key);
        if (found == keys.end()) {
            failDem(name,
                    "'" + shown(token) +
                        "' is not an ESRI ASCII grid header key (ncols, nrows, xllcorner, yllcorner, cellsize, "
                        "NODATA_value)",
                    line);
        }
        Field& f = fields[std::size_t(found - keys.begin())];
        if (f.set) failDem(name, "'" + key + "' is given twice", line);
        int valueLine = 0;
        const std::string_view value = tokens.next(valueLine);
        const std::optional<double> number = toNumber(value);
        if (valueLine != line || !number || !std::isfinite(*number)) {
            failDem(name,
                    "'" + key + "' needs a finite number on its line" +
                        (value.empty() || valueLine != line ? std::string() : ", not '" + shown(value) + "'"),
                    line);
        }
        f = {*number, line, true};
    }
    const auto require = [&](const char* key, const char* alternative = nullptr) -> const Field& {
        const Field& f = field(key);
        if (!f.set && !(alternative && field(alternative).set)) {
            failDem(name, std::string("the ESRI ASCII grid header lacks '") + key + "'" +
                              (alternative ? std::string(" (or '") + alternative + "')" : std::string()));
        }
        return f.set ? f : field(alternative);
    };
    const auto dimension = [&](const char* key) {
        const Field& f = require(key);
        if (f.value < 1.0 || f.value > double(MAX_DEM_DIMENSION) || f.value != std::floor(f.value)) {
            failDem(name,
                    std::string("'") + key + "' must be a whole number from 1 to 2147483647, not " +
                        formatNumber(f.value),
                    f.line);
        }
        return std::uint64_t(f.value);
    };
    const std::uint64_t columns = dimension("ncols"), rows = dimension("nrows");
    double cellSize = 0.0;
    int cellLine = 0;
    if (field("cellsize").set) {
        cellSize = field("cellsize").value, cellLine = field("cellsize").line;
        if (field("dx").set || field("dy").set)
            failDem(name, "give either 'cellsize' or 'dx' and 'dy', not both", cellLine);
    } else {
        const Field& dx = require("dx");
        const Field& dy = require("dy");
        if (dx.value != dy.value) {
            failDem(name,
                    "'dx' " + formatNumber(dx.value) + " and 'dy' " + formatNumber(dy.value) +
                        " differ: only square cells are supported",
                    dy.line);
        }
        cellSize = dx.value, cellLine = dx.line;
    }
    if (!(cellSize > 0.0)) failDem(name, "the cell size must be > 0, not " + formatNumber(cellSize), cellLine);
    for (const auto& [corner, centre] : {std::pair{"xllcorner", "xllcenter"}, std::pair{"yllcorner", "yllcenter"}}) {
        if (field(corner).set && field(centre).set) {
            failDem(name, std::string("give either '") + corner + "' or '" + centre + "', not both",
                    field(centre).line);
        }
    }
    const Field& x = require("xllcorner", "xllcenter");
    const Field& y = require("yllcorner", "yllcenter");
    const double half = 0.5 * cellSize;

    const std::uint64_t cells = demGridCells(rows, columns, name);
    // Every value takes at least one character and one separator (the last needs none).
    if (cells > tokens.remaining() / 2 + 1) {
        failDem(name, std::to_string(rows) + " rows of " + std::to_string(columns) + " values cannot fit in the " +
                          std::to_string(tokens.remaining()) + " bytes after the header (truncated file?)");
    }

    ElevationGrid grid;
    grid.format = "asc";
    grid.width = int(columns);
    grid.height = int(rows);
    grid.cellSize = cellSize;
    grid.lowerLeft = {field("xllcorner").set ? x.value : x.value - half,
                      field("yllcorner").set ? y.value : y.value - half};
    grid.heights.resize(std::size_t(cells));
    const Field& noData = field("nodata_value");
    for (std::uint64_t i = 0; i < cells; ++i) {
        const std::string_view token = tokens.next(line);
        if (token.empty()) {
            failDem(name,
                    "the grid ends after " + std::to_string(i) + " values; ncols x nrows = " + std::to_string(columns) +
                        " x " + std::to_string(rows) + " needs " + std::to_string(cells),
                    line);
        }
        const std::optional<double> number = toNumber(token);
        if (!number) {
            failDem(name,
                    "'" + shown(token) + "' is not a number (value " + std::to_string(i + 1) + " of " +
                        std::to_string(cells) + ")",
                    line);
        }
        double value = *number;
        if ((noData.set && value == noData.value) || !std::isfinite(value)) {
            value = std::numeric_limits<double>::quiet_NaN();
            ++grid.noDataCells;
        }
        grid.heights[std::size_t(i)] = value;
    }
    if (!tokens.next(line).empty()) {
        failDem(name, "more values than ncols x nrows = " + std::to_string(columns) + " x " + std::to_string(rows),
                line);
    }
    return grid;
}

} // namespace strata::terrain::detail
