// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/ElevationFile.h>

#include <strata/Error.h>

#include <zlib.h>
#include <strata/Format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace strata::terrain {

namespace {

constexpr std::uint64_t MAX_DIMENSION = std::uint64_t(std::numeric_limits<int>::max());
/// The most cells a DEM may have: 2^28, a 16384 x 16384 grid, 2 GiB of
/// heights as doubles. Larger grids (or a few bytes claiming one) are
/// refused before anything is allocated for them.
constexpr std::uint64_t MAX_CELLS = std::uint64_t(1) << 28;

[[noreturn]] void fail(const std::string& name, const std::string& what, int line = 0)
{
    ErrorPlace place;
    place.file = name;
    place.line = line;
    throw Error(ErrorKind::BadInput, name + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what,
                place);
}

/// rows * columns (each <= MAX_DIMENSION, so no overflow), at most MAX_CELLS.
std::uint64_t gridCells(std::uint64_t rows, std::uint64_t columns, const std::string& name)
{
    const std::uint64_t cells = rows * columns;
    if (cells > MAX_CELLS) {
        fail(name, std::to_string(rows) + " rows of " + std::to_string(columns) + " values are " + std::to_string(cells) +
                       " cells, more than the " + std::to_string(MAX_CELLS) +
                       " (16384 x 16384) a DEM may have: crop or resample it");
    }
    return cells;
}

// ---------------------------------------------------------------------------
// Little-endian fields, bounds-checked by the callers.

std::uint64_t readLittle(std::string_view bytes, std::size_t offset, int size)
{
    std::uint64_t value = 0;
    for (int i = size - 1; i >= 0; --i) value = (value << 8) | std::uint8_t(bytes[offset + std::size_t(i)]);
    return value;
}

/// True when [offset, offset + size) lies inside `bytes` (no overflow).
bool fits(std::string_view bytes, std::uint64_t offset, std::uint64_t size)
{
    return offset <= bytes.size() && size <= bytes.size() - offset;
}

// ---------------------------------------------------------------------------
// NumPy .npy

struct NpyHeader
{
    std::string descr;
    bool fortranOrder = false;
    std::vector<std::uint64_t> shape;
    std::size_t dataOffset = 0; ///< where the array's bytes start
};

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
    [[noreturn]] void bad(const std::string& what) const { fail(mName, what); }
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
                if (value > MAX_DIMENSION) bad("an array dimension is larger than 2147483647 in the .npy header");
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

constexpr std::string_view NPY_MAGIC("\x93NUMPY", 6);

NpyHeader parseNpyHeader(std::string_view bytes, const std::string& name)
{
    if (bytes.size() < 10 || bytes.substr(0, 6) != NPY_MAGIC)
        fail(name, "not a NumPy .npy array (no \\x93NUMPY magic)");
    const int major = std::uint8_t(bytes[6]);
    if (major < 1 || major > 3)
        fail(name, "NumPy .npy format version " + std::to_string(major) + " is not supported (1 to 3 are)");
    const int lengthSize = major == 1 ? 2 : 4;
    if (!fits(bytes, 8, std::uint64_t(lengthSize))) fail(name, "the .npy header is truncated");
    const std::uint64_t length = readLittle(bytes, 8, lengthSize);
    const std::uint64_t start = 8 + std::uint64_t(lengthSize);
    if (!fits(bytes, start, length)) {
        fail(name, "the .npy header says it is " + std::to_string(length) + " bytes long, more than the file holds");
    }
    if (length > 65536) fail(name, "the .npy header is " + std::to_string(length) + " bytes long (at most 65536)");
    NpyHeader header = DictParser(bytes.substr(std::size_t(start), std::size_t(length)), name).parse();
    header.dataOffset = std::size_t(start + length);
    return header;
}

std::string showShape(const std::vector<std::uint64_t>& shape)
{
    std::string text = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
    return text + (shape.size() == 1 ? ",)" : ")");
}

/// What a .npy header says of its array, checked: a supported type, two
/// dimensions, at most MAX_CELLS cells. `prefix` needs only hold the header.
struct NpyLayout
{
    NpyHeader header;
    std::uint64_t rows = 0, columns = 0, cells = 0;
    int itemSize = 0;
    bool isFloat = false;

    /// The bytes a whole .npy of this layout has.
    std::uint64_t fileSize() const { return header.dataOffset + cells * std::uint64_t(itemSize); }
};

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
        fail(name,
             "the array's type '" + header.descr +
                 "' is not supported (little-endian int16, int32, float32 or float64: '<i2', '<i4', '<f4', '<f8')");
    }
    if (header.shape.size() != 2) {
        fail(name, "the array has shape " + showShape(header.shape) + ": a DEM is a 2D array (rows, columns)");
    }
    layout.rows = header.shape[0];
    layout.columns = header.shape[1];
    if (layout.rows == 0 || layout.columns == 0) fail(name, "the array of shape " + showShape(header.shape) + " is empty");
    layout.cells = gridCells(layout.rows, layout.columns, name);
    return layout;
}

/// Refuses a .npy of `size` bytes whose data is not exactly the layout's.
void checkNpySize(const NpyLayout& layout, std::uint64_t size, const std::string& name)
{
    if (size != layout.fileSize()) {
        fail(name, "the array of shape " + showShape(layout.header.shape) + " and type '" + layout.header.descr +
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

// ---------------------------------------------------------------------------
// NumPy .npz (zip)

struct ZipEntry
{
    std::string name;
    int method = 0;
    int flags = 0;
    std::uint32_t crc = 0;
    std::uint64_t compressedSize = 0, size = 0, localOffset = 0;
};

/// The central directory of a zip archive (zip64 included).
std::vector<ZipEntry> zipDirectory(std::string_view bytes, const std::string& name)
{
    constexpr std::size_t EOCD_SIZE = 22;
    if (bytes.size() < EOCD_SIZE) fail(name, "not a zip archive (.npz): too short");
    // The end of central directory record, searched backwards (a comment may follow it).
    std::size_t eocd = std::string_view::npos;
    const std::size_t lowest = bytes.size() - EOCD_SIZE > 65535 ? bytes.size() - EOCD_SIZE - 65535 : 0;
    for (std::size_t at = bytes.size() - EOCD_SIZE + 1; at-- > lowest;) {
        if (bytes.substr(at, 4) == std::string_view("PK\x05\x06", 4)) {
            eocd = at;
            break;
        }
    }
    if (eocd == std::string_view::npos) fail(name, "not a zip archive (.npz): no end of central directory record");
    if (readLittle(bytes, eocd + 4, 2) != 0 || readLittle(bytes, eocd + 6, 2) != 0) {
        fail(name, "multi-part zip archives are not supported");
    }
    std::uint64_t count = readLittle(bytes, eocd + 10, 2);
    std::uint64_t directorySize = readLittle(bytes, eocd + 12, 4);
    std::uint64_t directoryOffset = readLittle(bytes, eocd + 16, 4);
    if (count == 0xFFFF || directorySize == 0xFFFFFFFF || directoryOffset == 0xFFFFFFFF) {
        // zip64: the locator (20 bytes) sits just before the record.
        if (eocd < 20 || bytes.substr(eocd - 20, 4) != std::string_view("PK\x06\x07", 4)) {
            fail(name, "zip64 archive without its end of central directory locator");
        }
        const std::uint64_t record = readLittle(bytes, eocd - 20 + 8, 8);
        if (!fits(bytes, record, 56) || bytes.substr(std::size_t(record), 4) != std::string_view("PK\x06\x06", 4)) {
            fail(name, "the zip64 end of central directory record is missing or truncated");
        }
        count = readLittle(bytes, std::size_t(record) + 32, 8);
        directorySize = readLittle(bytes, std::size_t(record) + 40, 8);
        directoryOffset = readLittle(bytes, std::size_t(record) + 48, 8);
    }
    if (!fits(bytes, directoryOffset, directorySize)) fail(name, "the zip central directory lies outside the file");
    if (count > directorySize / 46)
        fail(name, "the zip central directory is too small for its " + std::to_string(count) + " entries");

    std::vector<ZipEntry> entries;
    std::size_t at = std::size_t(directoryOffset);
    const std::size_t end = std::size_t(directoryOffset + directorySize);
    for (std::uint64_t i = 0; i < count; ++i) {
        if (end - at < 46 || bytes.substr(at, 4) != std::string_view("PK\x01\x02", 4)) {
            fail(name, "zip central directory entry " + std::to_string(i + 1) + " is malformed");
        }
        ZipEntry e;
        e.flags = int(readLittle(bytes, at + 8, 2));
        e.method = int(readLittle(bytes, at + 10, 2));
        e.crc = std::uint32_t(readLittle(bytes, at + 16, 4));
        e.compressedSize = readLittle(bytes, at + 20, 4);
        e.size = readLittle(bytes, at + 24, 4);
        const std::size_t nameLength = std::size_t(readLittle(bytes, at + 28, 2));
        const std::size_t extraLength = std::size_t(readLittle(bytes, at + 30, 2));
        const std::size_t commentLength = std::size_t(readLittle(bytes, at + 32, 2));
        e.localOffset = readLittle(bytes, at + 42, 4);
        if (end - at - 46 < nameLength + extraLength + commentLength) {
            fail(name, "zip central directory entry " + std::to_string(i + 1) + " runs past the directory");
        }
        e.name = std::string(bytes.substr(at + 46, nameLength));
        // zip64 extended information: the 64-bit forms of the fields set to 0xFFFFFFFF, in order.
        std::size_t extra = at + 46 + nameLength;
        const std::size_t extraEnd = extra + extraLength;
        while (extraEnd - extra >= 4) {
            const std::uint64_t id = readLittle(bytes, extra, 2);
            const std::size_t size = std::size_t(readLittle(bytes, extra + 2, 2));
            if (extraEnd - extra - 4 < size) fail(name, "zip entry '" + e.name + "' has a malformed extra field");
            if (id == 0x0001) {
                std::size_t field = extra + 4;
                for (std::uint64_t* value : {&e.size, &e.compressedSize, &e.localOffset}) {
                    if (*value != 0xFFFFFFFF) continue;
                    if (field + 8 > extra + 4 + size)
                        fail(name, "zip entry '" + e.name + "' has a truncated zip64 field");
                    *value = readLittle(bytes, field, 8);
                    field += 8;
                }
            }
            extra += 4 + size;
        }
        entries.push_back(std::move(e));
        at += 46 + nameLength + extraLength + commentLength;
    }
    return entries;
}

/// The first `limit` bytes of a member (all of it by default), stored
/// (method 0) or deflated (method 8, as np.savez_compressed and some
/// packagers write: inflated with zlib). Inflated a step at a time, so
/// memory follows the bytes the data really yields, never the size its
/// header claims; the CRC is checked when the whole member is read. Errors
/// for other methods, 4 GiB or more, more than 1032 times its packed size
/// (deflate's limit) and a failed CRC.
std::string zipMember(std::string_view bytes, const ZipEntry& e, const std::string& name,
                      std::uint64_t limit = std::numeric_limits<std::uint64_t>::max())
{
    if (e.flags & 1) fail(name, "member '" + e.name + "' is encrypted, which is not supported");
    if (e.method != 0 && e.method != 8) {
        fail(name, "member '" + e.name + "' uses zip compression method " + std::to_string(e.method) +
                       ", which is not supported (only stored and deflated members)");
    }
    if (e.method == 0 && e.compressedSize != e.size)
        fail(name, "stored member '" + e.name + "' has different packed and unpacked sizes");
    // zlib counts in 32 bits: 2^32 bytes would read as 0.
    constexpr std::uint64_t FOUR_GIB = std::uint64_t(1) << 32;
    if (e.size >= FOUR_GIB || e.compressedSize >= FOUR_GIB ||
        (e.method == 8 && e.size > 1032 * e.compressedSize + 1024))
        fail(name, "member '" + e.name + "' claims " + std::to_string(e.size) + " bytes, more than it can hold");
    if (!fits(bytes, e.localOffset, 30) ||
        bytes.substr(std::size_t(e.localOffset), 4) != std::string_view("PK\x03\x04", 4)) {
        fail(name, "member '" + e.name + "': its local header is missing or lies outside the file");
    }
    const std::uint64_t data = e.localOffset + 30 + readLittle(bytes, std::size_t(e.localOffset) + 26, 2) +
                               readLittle(bytes, std::size_t(e.localOffset) + 28, 2);
    if (!fits(bytes, data, e.compressedSize))
        fail(name, "member '" + e.name + "' runs past the end of the file (truncated?)");
    const std::string_view packed = bytes.substr(std::size_t(data), std::size_t(e.compressedSize));
    const bool whole = limit >= e.size;
    std::string content;
    if (e.method == 0) {
        content = std::string(packed.substr(0, std::size_t(std::min(limit, e.size))));
    } else {
        // One byte more than the member claims when reading it whole, so a
        // stream that yields more is seen.
        const std::uint64_t room = whole ? e.size + 1 : limit;
        z_stream stream{};
        if (inflateInit2(&stream, -MAX_WBITS) != Z_OK) fail(name, "zlib could not start inflating");
        stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(packed.data()));
        stream.avail_in = uInt(packed.size());
        int status = Z_OK;
        while (status == Z_OK && content.size() < room) {
            const std::size_t have = content.size();
            const std::size_t step = std::size_t(std::min<std::uint64_t>(room - have, std::uint64_t(1) << 20));
            content.resize(have + step);
            stream.next_out = reinterpret_cast<Bytef*>(content.data() + have);
            stream.avail_out = uInt(step);
            status = inflate(&stream, Z_NO_FLUSH);
            content.resize(have + step - stream.avail_out);
        }
        inflateEnd(&stream);
        const bool complete = whole ? status == Z_STREAM_END && content.size() == e.size
                                    : content.size() == limit || status == Z_STREAM_END;
        if (!complete) {
            fail(name, "member '" + e.name + "' is not valid deflate data of " + std::to_string(e.size) +
                           " bytes (corrupt file)");
        }
    }
    if (whole && ::crc32(0L, reinterpret_cast<const Bytef*>(content.data()), uInt(content.size())) != e.crc)
        fail(name, "member '" + e.name + "' fails its CRC-32 check (corrupt file)");
    return content;
}

/// Enough of a .npy member to hold its header (at most 64 KiB long).
constexpr std::uint64_t NPY_HEADER_BYTES = 12 + 65536;

ElevationGrid parseNpz(std::string_view bytes, const std::string& name)
{
    const std::vector<ZipEntry> entries = zipDirectory(bytes, name);
    auto isArray = [](const ZipEntry& e) { return e.name.size() > 4 && e.name.ends_with(".npy"); };
    const ZipEntry* chosen = nullptr;
    for (const ZipEntry& e : entries) {
        if (e.name == "elevation.npy") chosen = &e;
    }
    if (!chosen) {
        // The only 2D array, found by each member's header alone.
        std::vector<const ZipEntry*> planes;
        std::string names;
        for (const ZipEntry& e : entries) {
            if (!isArray(e)) continue;
            names += (names.empty() ? "" : ", ") + e.name;
            const NpyHeader header =
                parseNpyHeader(zipMember(bytes, e, name, NPY_HEADER_BYTES), name + " member '" + e.name + "'");
            if (header.shape.size() == 2) planes.push_back(&e);
        }
        if (planes.size() > 1) {
            std::string list;
            for (const ZipEntry* e : planes) list += (list.empty() ? "" : ", ") + e->name;
            fail(name,
                 "holds several 2D arrays (" + list + ") and none named 'elevation': save the DEM as 'elevation'");
        }
        if (planes.empty()) {
            fail(name, "holds no 2D array" +
                           (names.empty() ? std::string(" (no .npy member at all)") : " (arrays: " + names + ")"));
        }
        chosen = planes.front();
    }
    // The header's layout against the member's size before inflating it all.
    const std::string member = name + " member '" + chosen->name + "'";
    checkNpySize(npyLayout(zipMember(bytes, *chosen, name, NPY_HEADER_BYTES), member), chosen->size, member);
    ElevationGrid grid = parseNpy(zipMember(bytes, *chosen, name), member);
    grid.format = "npz";
    grid.member = chosen->name;
    return grid;
}

// ---------------------------------------------------------------------------
// ESRI ASCII grid

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

ElevationGrid parseAsc(std::string_view text, const std::string& name)
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
            fail(name,
                 "'" + shown(token) +
                     "' is not an ESRI ASCII grid header key (ncols, nrows, xllcorner, yllcorner, cellsize, "
                     "NODATA_value)",
                 line);
        }
        Field& f = fields[std::size_t(found - keys.begin())];
        if (f.set) fail(name, "'" + key + "' is given twice", line);
        int valueLine = 0;
        const std::string_view value = tokens.next(valueLine);
        const std::optional<double> number = toNumber(value);
        if (valueLine != line || !number || !std::isfinite(*number)) {
            fail(name,
                 "'" + key + "' needs a finite number on its line" +
                     (value.empty() || valueLine != line ? std::string() : ", not '" + shown(value) + "'"),
                 line);
        }
        f = {*number, line, true};
    }
    const auto require = [&](const char* key, const char* alternative = nullptr) -> const Field& {
        const Field& f = field(key);
        if (!f.set && !(alternative && field(alternative).set)) {
            fail(name, std::string("the ESRI ASCII grid header lacks '") + key + "'" +
                           (alternative ? std::string(" (or '") + alternative + "')" : std::string()));
        }
        return f.set ? f : field(alternative);
    };
    const auto dimension = [&](const char* key) {
        const Field& f = require(key);
        if (f.value < 1.0 || f.value > double(MAX_DIMENSION) || f.value != std::floor(f.value)) {
            fail(name,
                 std::string("'") + key + "' must be a whole number from 1 to 2147483647, not " + formatNumber(f.value),
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
            fail(name, "give either 'cellsize' or 'dx' and 'dy', not both", cellLine);
    } else {
        const Field& dx = require("dx");
        const Field& dy = require("dy");
        if (dx.value != dy.value) {
            fail(name,
                 "'dx' " + formatNumber(dx.value) + " and 'dy' " + formatNumber(dy.value) +
                     " differ: only square cells are supported",
                 dy.line);
        }
        cellSize = dx.value, cellLine = dx.line;
    }
    if (!(cellSize > 0.0)) fail(name, "the cell size must be > 0, not " + formatNumber(cellSize), cellLine);
    for (const auto& [corner, centre] : {std::pair{"xllcorner", "xllcenter"}, std::pair{"yllcorner", "yllcenter"}}) {
        if (field(corner).set && field(centre).set) {
            fail(name, std::string("give either '") + corner + "' or '" + centre + "', not both", field(centre).line);
        }
    }
    const Field& x = require("xllcorner", "xllcenter");
    const Field& y = require("yllcorner", "yllcenter");
    const double half = 0.5 * cellSize;

    const std::uint64_t cells = gridCells(rows, columns, name);
    // Every value takes at least one character and one separator (the last needs none).
    if (cells > tokens.remaining() / 2 + 1) {
        fail(name, std::to_string(rows) + " rows of " + std::to_string(columns) + " values cannot fit in the " +
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
            fail(name,
                 "the grid ends after " + std::to_string(i) + " values; ncols x nrows = " + std::to_string(columns) +
                     " x " + std::to_string(rows) + " needs " + std::to_string(cells),
                 line);
        }
        const std::optional<double> number = toNumber(token);
        if (!number) {
            fail(name,
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
        fail(name, "more values than ncols x nrows = " + std::to_string(columns) + " x " + std::to_string(rows), line);
    }
    return grid;
}

} // namespace

ElevationGrid parseElevationFile(std::string_view bytes, const std::string& name)
{
    if (bytes.substr(0, 6) == NPY_MAGIC) return parseNpy(bytes, name);
    if (bytes.substr(0, 4) == std::string_view("PK\x03\x04", 4) ||
        bytes.substr(0, 4) == std::string_view("PK\x05\x06", 4)) {
        return parseNpz(bytes, name);
    }
    if (bytes.empty()) fail(name, "the file is empty");
    if (bytes.find('\0') != std::string_view::npos) {
        fail(name, "not a DEM file Strata reads (NumPy .npy, .npz or an ESRI ASCII grid .asc)");
    }
    return parseAsc(bytes, name);
}

ElevationGrid readElevationFile(const std::filesystem::path& path)
{
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail(name, "is a directory, not a DEM file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(name, "cannot open the DEM file");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail(name, "cannot read the DEM file");
    return parseElevationFile(bytes, name);
}

} // namespace strata::terrain
