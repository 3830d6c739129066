// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "NpyReader.h"

#include "ElevationFileCommon.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <limits>

namespace strata::terrain::detail {

namespace {

/// The header's Python dict literal, e.g.
/// {'descr': '<i2', 'fortran_order': False, 'shape': (344, 403), }
class DictParser
{
public:
    DictParser(std::string_view text, const std::string& name) : mText(text), mName(name) {}

    NpyHeader parse()
    {
        NpyHeader header;
        bool haveDescr = false, haveOrder = false, haveShape = false;
        expect('{');
        for (;;) {
            skipSpace();
            if (peek() == '}') break;
            const std::string key = quoted();
            expect(':');
            skipSpace();
            if (key == "descr") {
                header.descr = quoted();
                haveDescr = true;
            } else if (key == "fortran_order") {
                header.fortranOrder = boolean();
                haveOrder = true;
            } else if (key == "shape") {
                header.shape = tuple();
                haveShape = true;
            } else {
                bad("unknown key '" + key + "' in the .npy header");
            }
            skipSpace();
            if (peek() == ',') {
                ++mPos;
                continue;
            }
            if (peek() != '}') bad("expected ',' or '}' in the .npy header");
        }
        if (!haveDescr || !haveOrder || !haveShape) {
            bad("the .npy header lacks '" +
                std::string(!haveDescr   ? "descr"
                            : !haveOrder ? "fortran_order"
                                         : "shape") +
                "'");
        }
        return header;
    }

private:
    [[noreturn]] void bad(const std::string& what) const { failDem(mName, what); }
    char peek() const { return mPos < mText.size() ? mText[mPos] : '\0'; }
    void skipSpace()
    {
        while (mPos < mText.size() &&
               (mText[mPos] == ' ' || mText[mPos] == '\t' || mText[mPos] == '\n' || mText[mPos] == '\r'))
            ++mPos;
    }
    void expect(char c)
    {
        skipSpace();
        if (peek() != c) bad(std::string("expected '") + c + "' in the .npy header");
        ++mPos;
    }
    std::string quoted()
    {
        skipSpace();
        const char quote = peek();
        if (quote != '\'' && quote != '"') bad("expected a quoted string in the .npy header");
        const std::size_t end = mText.find(quote, mPos + 1);
        if (end == std::string_view::npos || end - mPos > 64) bad("unterminated or overlong string in the .npy header");
        const std::string text(mText.substr(mPos + 1, end - mPos - 1));
        mPos = end + 1;
        return text;
    }
    bool boolean()
    {
        if (mText.substr(mPos, 4) == "True") {
            mPos += 4;
            return true;
        }
        if (mText.substr(mPos, 5) == "False") {
            mPos += 5;
            return false;
        }
        bad("'fortran_order' must be True or False in the .npy header");
    }
    std::vector<std::uint64_t> tuple()
    {
        if (peek() != '(') bad("'shape' must be a tuple in the .npy header");
        ++mPos;
        std::vector<std::uint64_t> shape;
        for (;;) {
            skipSpace();
            if (peek() == ')') break;
            if (!std::isdigit(static_cast<unsigned char>(peek()))) bad("'shape' must hold integers in the .npy header");
            std::uint64_t value = 0;
            while (std::isdigit(static_cast<unsigned char>(peek()))) {
                value = value * 10 + std::uint64_t(peek() - '0');
                if (value > MAX_DEM_DIMENSION) bad("an array dimension is larger than 2147483647 in the .npy header");
                ++mPos;
            }
            if (peek() == 'L') ++mPos; // Python 2 long
            if (shape.size() >= 32) bad("'shape' has too many dimensions in the .npy header");
            shape.push_back(value);
            skipSpace();
            if (peek() == ',') {
                ++mPos;
                continue;
            }
            if (peek() != ')') bad("expected ',' or ')' in the .npy 'shape'");
        }
        ++mPos;
        return shape;
    }

    std::string_view mText;
    const std::string& mName;
    std::size_t mPos = 0;
};

std::string showShape(const std::vector<std::uint64_t>& shape)
{
    std::string text = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
    return text + (shape.size() == 1 ? ",)" : ")");
}

} // namespace

NpyHeader parseNpyHeader(std::string_view bytes, const std::string& name)
{
    if (bytes.size() < 10 || bytes.substr(0, 6) != NPY_MAGIC)
        failDem(name, "not a NumPy .npy array (no \\x93NUMPY magic)");
    const int major = std::uint8_t(bytes[6]);
    if (major < 1 || major > 3)
        failDem(name, "NumPy .npy format version " + std::to_string(major) + " is not supported (1 to 3 are)");
    const int lengthSize = major == 1 ? 2 : 4;
    if (!fitsIn(bytes, 8, std::uint64_t(lengthSize))) failDem(name, "the .npy header is truncated");
    const std::uint64_t length = readLittle(bytes, 8, lengthSize);
    const std::uint64_t start = 8 + std::uint64_t(lengthSize);
    if (!fitsIn(bytes, start, length)) {
        failDem(name, "the .npy header says it is " + std::to_string(length) + " bytes long, more than the file holds");
    }
    if (length > 65536) failDem(name, "the .npy header is " + std::to_string(length) + " bytes long (at most 65536)");
    NpyHeader header = DictParser(bytes.substr(std::size_t(start), std::size_t(length)), name).parse();
    header.dataOffset = std::size_t(start + length);
    return header;
}

NpyLayout npyLayout(std::string_view prefix, const std::string& name)
{
    NpyLayout layout;
    layout.header = parseNpyHeader(prefix, name);
    const NpyHeader& header = layout.header;
    if (header.descr == "<i2")
        layout.itemSize = 2;
    else if (header.descr == "<i4")
        layout.itemSize = 4;
    else if (header.descr == "<f4")
        layout.itemSize = 4, layout.isFloat = true;
    else if (header.descr == "<f8")
        layout.itemSize = 8, layout.isFloat = true;
    else {
        failDem(name,
                "the array's type '" + header.descr +
                    "' is not supported (little-endian int16, int32, float32 or float64: '<i2', '<i4', '<f4', '<f8')");
    }
    if (header.shape.size() != 2) {
        failDem(name, "the array has shape " + showShape(header.shape) + ": a DEM is a 2D array (rows, columns)");
    }
    layout.rows = header.shape[0];
    layout.columns = header.shape[1];
    if (layout.rows == 0 || layout.columns == 0)
        failDem(name, "the array of shape " + showShape(header.shape) + " is empty");
    layout.cells = demGridCells(layout.rows, layout.columns, name);
    return layout;
}

/// Refuses a .npy of `size` bytes whose data is not exactly the layout's.
void checkNpySize(const NpyLayout& layout, std::uint64_t size, const std::string& name)
{
    if (size != layout.fileSize()) {
        failDem(name, "the array of shape " + showShape(layout.header.shape) + " and type '" + layout.header.descr +
                          "' needs " + std::to_string(layout.cells) + " x " + std::to_string(layout.itemSize) +
                          " bytes, the file holds " + std::to_string(size - std::min(size, layout.header.dataOffset)) +
                          " after the header");
    }
}

ElevationGrid parseNpy(std::string_view bytes, const std::string& name)
{
    const NpyLayout layout = npyLayout(bytes, name);
    checkNpySize(layout, bytes.size(), name);
    const NpyHeader& header = layout.header;
    const std::uint64_t rows = layout.rows, columns = layout.columns, cells = layout.cells;
    const std::uint64_t available = bytes.size() - header.dataOffset;
    const int itemSize = layout.itemSize;
    const bool isFloat = layout.isFloat;

    ElevationGrid grid;
    grid.format = "npy";
    grid.width = int(columns);
    grid.height = int(rows);
    grid.heights.resize(std::size_t(cells));
    const char* data = bytes.data() + header.dataOffset;
    for (std::uint64_t i = 0; i < cells; ++i) {
        const std::uint64_t raw = readLittle(std::string_view(data, std::size_t(available)),
                                             std::size_t(i) * std::size_t(itemSize), itemSize);
        double value = 0.0;
        if (!isFloat) {
            value = itemSize == 2 ? double(std::int16_t(std::uint16_t(raw))) : double(std::int32_t(std::uint32_t(raw)));
        } else {
            value = itemSize == 4 ? double(std::bit_cast<float>(std::uint32_t(raw))) : std::bit_cast<double>(raw);
        }
        if (!std::isfinite(value)) {
            value = std::numeric_limits<double>::quiet_NaN();
            ++grid.noDataCells;
        }
        // Fortran order stores the columns one after another.
        const std::uint64_t at = header.fortranOrder ? (i % rows) * columns + i / rows : i;
        grid.heights[std::size_t(at)] = value;
    }
    return grid;
}

} // namespace strata::terrain::detail
