// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "VdbPreflight.h"

#include <strata/Error.h>

#include <openvdb/Metadata.h>
#include <openvdb/io/Compression.h>
#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/math/Maps.h>
#include <openvdb/openvdb.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>

namespace strata::meshing::detail {

namespace {

/// Bounds-checked little-endian reads from the file.
class Reader
{
public:
    explicit Reader(const std::filesystem::path& path)
        : mPath(path), mIn(path, std::ios::binary)
    {
        std::error_code ec;
        mSize = std::filesystem::file_size(path, ec);
        if (ec || !mIn) fail("cannot be opened");
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        throw Error(ErrorKind::BadInput, "VDB file '" + mPath.string() + "' " + what, {.file = mPath.string()});
    }

    std::uint64_t offset() const { return mOffset; }
    std::uint64_t remaining() const { return mSize - mOffset; }

    void bytes(void* out, std::uint64_t n, const char* what)
    {
        if (n > remaining()) {
            fail("is truncated or corrupt: " + std::string(what) + " at byte " + std::to_string(mOffset) +
                 " needs " + std::to_string(n) + " bytes, the file has " + std::to_string(remaining()) + " left");
        }
        if (!mIn.read(static_cast<char*>(out), std::streamsize(n))) fail("cannot be read at byte " + std::to_string(mOffset));
        mOffset += n;
    }
    template <typename T> T value(const char* what)
    {
        T v{};
        bytes(&v, sizeof(T), what);
        return v;
    }
    void skip(std::uint64_t n, const char* what)
    {
        if (n > remaining()) bytes(nullptr, n, what); // fails with the message
        seek(mOffset + n);
    }
    void seek(std::uint64_t to)
    {
        if (to > mSize) fail("is truncated or corrupt: an offset points to byte " + std::to_string(to) + " of " + std::to_string(mSize));
        mIn.seekg(std::streamoff(to));
        mOffset = to;
    }
    /// OpenVDB's string: a 32-bit length, then the characters.
    std::string string(const char* what)
    {
        const auto length = value<std::uint32_t>(what);
        if (length > remaining()) {
            fail("is truncated or corrupt: " + std::string(what) + " at byte " + std::to_string(mOffset - 4) +
                 " claims " + std::to_string(length) + " characters, the file has " + std::to_string(remaining()) +
                 " bytes left");
        }
        std::string s(length, '\0');
        bytes(s.data(), length, what);
        return s;
    }

private:
    std::filesystem::path mPath;
    std::ifstream mIn;
    std::uint64_t mSize = 0;
    std::uint64_t mOffset = 0;
};

/// A blosc 1 block of `count` bytes at the reader's position (block start
/// `at`): its header (version, version, flags, type size, then the
/// uncompressed size, the block size and the compressed size, 32-bit each)
/// must say `expected` bytes in `count`, since blosc trusts it. Leaves the
/// reader after the header.
void checkBloscHeader(Reader& r, std::uint64_t at, std::uint64_t count, std::uint64_t expected,
                      const std::string& what)
{
    if (count < 16) r.fail("is corrupt: " + what + " at byte " + std::to_string(at) + " is too short for blosc");
    std::uint8_t header[16] = {};
    r.bytes(header, 16, what.c_str());
    std::uint32_t nbytes = 0, cbytes = 0;
    std::memcpy(&nbytes, header + 4, 4);
    std::memcpy(&cbytes, header + 12, 4);
    if (nbytes != expected || cbytes != count) {
        r.fail("is corrupt: " + what + " at byte " + std::to_string(at) + ": its blosc header says " +
               std::to_string(nbytes) + " bytes in " + std::to_string(cbytes) + ", not " + std::to_string(expected) +
               " in " + std::to_string(count));
    }
}

/// MetaMap::readMeta: a count, then name, type name, byte count and value.
void checkMetadata(Reader& r, const char* where)
{
    const auto count = r.value<std::uint32_t>("a metadata count");
    // Each entry takes at least 12 bytes (three lengths).
    if (std::uint64_t(count) * 12 > r.remaining()) {
        r.fail("is truncated or corrupt: " + std::string(where) + " metadata at byte " + std::to_string(r.offset() - 4) +
               " claims " + std::to_string(count) + " entries");
    }
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::string name = r.string("a metadata name");
        const std::string type = r.string("a metadata type name");
        const auto size = r.value<std::uint32_t>("a metadata size");
        if (type == openvdb::io::DelayedLoadMetadata::staticTypeName()) {
            // A 32-bit count of leaves comes first, and OpenVDB sizes two
            // arrays by it (a byte and a 64-bit size per leaf); both are
            // stored compressed, but per-leaf sizes never shrink 64-fold.
            // DelayedLoadMetadata::readValue then reads, whatever the size
            // says, a byte count and the masks (blosc or raw), and a byte
            // count (all ones: none) and the sizes: all of it must lie within
            // the value, each blosc block agree with its header.
            if (size > 0) {
                const std::uint64_t start = r.offset();
                if (size > r.remaining()) r.skip(size, "a metadata value"); // fails with the message
                const std::string what = "metadata '" + name + "'";
                auto within = [&](std::uint64_t n) {
                    if (r.offset() + n > start + size) {
                        r.fail("is corrupt: " + what + " at byte " + std::to_string(start) + " reads past its " +
                               std::to_string(size) + " bytes");
                    }
                };
                within(8);
                const auto masks = r.value<std::uint32_t>("a delayed-load mask count");
                if (std::uint64_t(masks) > 64 * std::uint64_t(size)) {
                    r.fail("is corrupt: " + what + " at byte " + std::to_string(start) + " claims " +
                           std::to_string(masks) + " masks in " + std::to_string(size) + " bytes");
                }
                for (const std::uint64_t itemSize : {std::uint64_t(1), std::uint64_t(8)}) { // masks, then sizes
                    if (itemSize == 8) within(4);
                    const std::uint64_t at = r.offset();
                    const auto bytes = r.value<std::uint32_t>("a delayed-load block size");
                    if (itemSize == 8 && bytes == 0xffffffffu) break; // no sizes stored
                    if (bytes > 0) {
                        within(bytes);
                        checkBloscHeader(r, at, bytes, masks * itemSize, what);
                        r.seek(at + 4 + bytes);
                    } else {
                        within(masks * itemSize);
                        r.skip(masks * itemSize, "delayed-load values");
                    }
                }
                r.seek(start);
            }
        } else if (type != openvdb::StringMetadata::staticTypeName() && openvdb::Metadata::isRegisteredType(type)) {
            // Typed metadata is read with the size of its type whatever the
            // file says: a mismatch would put the reader out of step.
            const openvdb::Metadata::Ptr expected = openvdb::Metadata::createMetadata(type);
            if (expected && expected->size() != size) {
                r.fail("is corrupt: metadata '" + name + "' of type " + type + " at byte " + std::to_string(r.offset() - 4) +
                       " has " + std::to_string(size) + " bytes, not " + std::to_string(expected->size()));
            }
        }
        r.skip(size, "a metadata value");
    }
}

/// The size in bytes of a value of `grid`'s tree as the root node stores its
/// background and tile values (sizeof(ValueType), also for half-float
/// grids): measured from what an empty tree of that type writes (the tree's
/// buffer count, the background, the tile and child counts), so it holds for
/// every registered grid type.
std::uint64_t rootValueSize(const openvdb::GridBase& grid)
{
    std::ostringstream out(std::ios::binary);
    grid.writeTopology(out);
    const std::uint64_t written = out.str().size();
    return written - sizeof(std::int32_t) - 2 * sizeof(openvdb::Index);
}

/// The bytes a registered map's read() consumes after its type name
/// (openvdb/math/Maps.h), or -1 for a type this check does not know (a map
/// registered by someone else: OpenVDB reads it, and the check stops there).
std::int64_t mapSize(Reader& r, const std::string& type, int depth)
{
    constexpr std::int64_t VEC3D = 3 * sizeof(double);
    if (type == "AffineMap" || type == "UnitaryMap") return 16 * sizeof(double); // a Mat4d
    if (type == "ScaleMap" || type == "UniformScaleMap") return 5 * VEC3D;
    if (type == "TranslationMap") return VEC3D;
    if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") return 6 * VEC3D;
    if (type == "NonlinearFrustumMap") {
        // A BBoxd, the taper and the depth, then a second map by type name.
        r.skip(2 * VEC3D + 2 * sizeof(double), "a frustum map");
        // OpenVDB writes an AffineMap there; a frustum in a frustum reads, but
        // no writer nests them deeply.
        if (depth >= 16) r.fail("is corrupt: frustum maps nested 16 deep at byte " + std::to_string(r.offset()));
        const std::string second = r.string("a frustum's second map type");
        if (!openvdb::math::MapRegistry::isRegistered(second)) return -1; // OpenVDB refuses it
        return mapSize(r, second, depth + 1);
    }
    return -1;
}

/// A grid descriptor (io::GridDescriptor::read).
struct Descriptor
{
    std::string type; ///< the grid type, without the "_HalfFloat" suffix
    bool half = false; ///< the type had the suffix: real values are stored as halves
    bool instance = false;
    std::int64_t gridPos = 0, blockPos = 0, endPos = 0;
    std::uint64_t end = 0; ///< the byte after the descriptor
};

Descriptor checkDescriptor(Reader& r)
{
    Descriptor d;
    r.string("a grid name");
    d.type = r.string("a grid type");
    static const std::string HALF = "_HalfFloat";
    if (d.type.size() >= HALF.size() && d.type.compare(d.type.size() - HALF.size(), HALF.size(), HALF) == 0) {
        d.type.resize(d.type.size() - HALF.size());
        d.half = true;
    }
    d.instance = !r.string("an instance parent name").empty(); // file versions 216 and later
    d.gridPos = r.value<std::int64_t>("a grid offset");
    d.blockPos = r.value<std::int64_t>("a grid offset");
    d.endPos = r.value<std::int64_t>("a grid offset");
    d.end = r.offset();
    return d;
}

/// The byte at `offset` (already read past) must be 0 or 1: OpenVDB reads
/// it straight into a bool, and any other byte is undefined behaviour.
void checkBool(Reader& r, std::uint64_t offset, const std::string& what)
{
    const std::uint64_t back = r.offset();
    r.seek(offset);
    const auto byte = r.value<std::uint8_t>(what.c_str());
    r.seek(back);
    if (byte > 1) {
        r.fail("is corrupt: " + what + " at byte " + std::to_string(offset) + " is " + std::to_string(byte) +
               ", not a bool (0 or 1)");
    }
}

/// How a tree of one of OpenVDB's standard 5-4-3 value types stores its
/// values below the root node (InternalNode and LeafNode<T, 3>).
struct ValueLayout
{
    std::uint64_t valueSize = 0;  ///< sizeof(ValueType): inactive values in the node records
    std::uint64_t storedSize = 0; ///< the size of a stored value (a half for half-float grids)
    bool halves = false;          ///< stored as halves: io::HalfReader reads nothing for no values
    std::uint32_t compression = 0; ///< the grid's io::COMPRESS_* flags
};

/// The layout of `d`'s tree below the root, or nothing for a type whose
/// leaves are not plain value arrays (bool, mask and point grids): their
/// nodes are not checked.
std::optional<ValueLayout> valueLayout(const Descriptor& d, std::uint64_t valueSize)
{
    struct Type
    {
        const char* name;
        std::uint64_t halfSize; ///< 0: not a real type (HalfReader<false> reads the values as they are)
    };
    static const Type TYPES[] = {{"Tree_float_5_4_3", 2}, {"Tree_double_5_4_3", 2}, {"Tree_vec3s_5_4_3", 6},
                                 {"Tree_vec3d_5_4_3", 6}, {"Tree_int32_5_4_3", 0},  {"Tree_int64_5_4_3", 0},
                                 {"Tree_vec3i_5_4_3", 0}};
    for (const Type& type : TYPES) {
        if (d.type == type.name) {
            ValueLayout layout;
            layout.valueSize = valueSize;
            layout.halves = d.half && type.halfSize;
            layout.storedSize = layout.halves ? type.halfSize : valueSize;
            return layout;
        }
    }
    return std::nullopt;
}

/// A compressed block as io::readData reads it: with blosc or zip, a 64-bit
/// byte count (negative: stored uncompressed) and the bytes. OpenVDB 10
/// allocates whatever a positive count says, and reads a negative count's
/// bytes into a buffer of the expected size before comparing the two (an
/// overflow): both are checked here first. A blosc block's own header
/// (uncompressed and compressed sizes) must agree, since blosc trusts it.
void checkDataBlock(Reader& r, std::uint64_t expected, std::uint32_t compression, const std::string& what)
{
    if (!(compression & (openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ZIP))) {
        r.skip(expected, what.c_str());
        return;
    }
    const std::uint64_t at = r.offset();
    const auto count = r.value<std::int64_t>(what.c_str());
    if (count <= 0) {
        const std::uint64_t raw = count == 0 ? 0 : std::uint64_t(-(count + 1)) + 1; // |count|, also for INT64_MIN
        if (raw != expected) {
            r.fail("is corrupt: " + what + " at byte " + std::to_string(at) + " holds " + std::to_string(raw) +
                   " uncompressed bytes, not " + std::to_string(expected));
        }
        r.skip(expected, what.c_str());
        return;
    }
    if (std::uint64_t(count) > r.remaining()) {
        r.fail("is truncated or corrupt: " + what + " at byte " + std::to_string(at) + " claims " +
               std::to_string(count) + " compressed bytes, the file has " + std::to_string(r.remaining()) + " left");
    }
    if (compression & openvdb::io::COMPRESS_BLOSC) {
        checkBloscHeader(r, at, std::uint64_t(count), expected, what);
        r.skip(std::uint64_t(count) - 16, what.c_str());
    } else {
        r.skip(std::uint64_t(count), what.c_str());
    }
}

/// A node mask of `bits` bits, read.
std::vector<std::uint8_t> readMask(Reader& r, std::uint64_t bits, const char* what)
{
    std::vector<std::uint8_t> mask(bits / 8);
    r.bytes(mask.data(), mask.size(), what);
    return mask;
}

/// The children a mask's set bits name.
std::uint64_t countOn(const std::vector<std::uint8_t>& mask)
{
    std::uint64_t n = 0;
    for (const std::uint8_t byte : mask) n += std::uint64_t(std::popcount(byte));
    return n;
}

/// A node's values as io::readCompressedValues reads them (file versions
/// 222 and later): the metadata byte, up to two inactive values, a selection
/// mask, then the values (only the active ones with mask compression).
void checkCompressedValues(Reader& r, const ValueLayout& layout, std::uint64_t count,
                           const std::vector<std::uint8_t>& valueMask, const std::string& what)
{
    const auto metadata = r.value<std::int8_t>("a node's compression metadata");
    // io/Compression.h: NO_MASK_AND_ONE_INACTIVE_VAL 2, MASK_AND_NO_INACTIVE_VALS 3,
    // MASK_AND_ONE_INACTIVE_VAL 4, MASK_AND_TWO_INACTIVE_VALS 5, NO_MASK_AND_ALL_VALS 6.
    if (metadata == 2 || metadata == 4 || metadata == 5) r.skip(layout.valueSize, "an inactive value");
    if (metadata == 5) r.skip(layout.valueSize, "an inactive value");
    if (metadata == 3 || metadata == 4 || metadata == 5) r.skip(valueMask.size(), "a selection mask");
    const bool maskCompressed = (layout.compression & openvdb::io::COMPRESS_ACTIVE_MASK) && metadata != 6;
    const std::uint64_t stored = maskCompressed ? countOn(valueMask) : count;
    if (layout.halves && stored == 0) return;
    checkDataBlock(r, stored * layout.storedSize, layout.compression, what);
}

/// The tree below the root node's tiles for `children` root children:
/// each child's topology (InternalNode<5>: child and value masks of 32768
/// bits, its values, its children; InternalNode<4>: 4096 bits; leaves: a
/// 512-bit value mask), then the leaves' buffers (a value mask and the
/// values) for the children the root keeps (one per origin: a later child
/// of the same origin replaces an earlier one).
void checkTree(Reader& r, const ValueLayout& layout, std::uint32_t children, const std::string& grid)
{
    std::map<std::array<std::int32_t, 3>, std::uint64_t> leavesByOrigin;
    for (std::uint32_t c = 0; c < children; ++c) {
        std::array<std::int32_t, 3> origin{};
        r.bytes(origin.data(), sizeof(origin), "a root child's origin");
        const std::string node = grid + "'s root child " + std::to_string(c);
        const std::vector<std::uint8_t> childMask5 = readMask(r, 32768, "an internal node's child mask");
        const std::vector<std::uint8_t> valueMask5 = readMask(r, 32768, "an internal node's value mask");
        checkCompressedValues(r, layout, 32768, valueMask5, node + "'s values");
        std::uint64_t leaves = 0;
        for (std::uint64_t i = 0, n = countOn(childMask5); i < n; ++i) {
            const std::vector<std::uint8_t> childMask4 = readMask(r, 4096, "an internal node's child mask");
            const std::vector<std::uint8_t> valueMask4 = readMask(r, 4096, "an internal node's value mask");
            checkCompressedValues(r, layout, 4096, valueMask4, node + "'s internal node values");
            const std::uint64_t n4 = countOn(childMask4);
            r.skip(n4 * 64, "leaf value masks");
            leaves += n4;
        }
        leavesByOrigin[origin] = leaves;
    }
    std::uint64_t leaves = 0;
    for (const auto& [origin, n] : leavesByOrigin) leaves += n;
    for (std::uint64_t i = 0; i < leaves; ++i) {
        const std::vector<std::uint8_t> valueMask = readMask(r, 512, "a leaf's value mask");
        checkCompressedValues(r, layout, 512, valueMask, grid + "'s leaf " + std::to_string(i) + " values");
    }
}

/// One grid after its descriptor, as io::Archive::readGrid reads it (OpenVDB
/// 10, file versions 222 and later): the grid's compression flags, its
/// metadata, its transform (type name and map), then, unless the grid is an
/// instance, its tree's topology as far as the root node's tiles: the buffer
/// count, the background, the tile and child counts and every tile record
/// (origin, value, active byte). RootNode::readTopology reads the active
/// byte (and a bool grid's values) straight into a bool, so a byte other
/// than 0 or 1 is refused here. A map or grid type that OpenVDB does not
/// know ends the check: OpenVDB refuses it before reading further. Returns
/// whether the grid was followed to its end (not for bool, mask or point
/// trees, whose nodes below the root are not checked).
bool checkGrid(Reader& r, const Descriptor& d, std::uint32_t fileVersion, std::int32_t index)
{
    const std::string grid = "grid " + std::to_string(index);
    std::uint32_t compression = 0;
    if (fileVersion >= openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION) {
        compression = r.value<std::uint32_t>("a grid's compression flags");
    }
    checkMetadata(r, "a grid's");
    const std::string transform = r.string("a transform type");
    if (!openvdb::math::MapRegistry::isRegistered(transform)) return false;
    const std::int64_t map = mapSize(r, transform, 0);
    if (map < 0) return false;
    r.skip(std::uint64_t(map), "a transform");
    if (d.instance) return true; // an instance has no tree of its own
    if (!openvdb::GridBase::isRegistered(d.type)) return false;
    const openvdb::GridBase::Ptr empty = openvdb::GridBase::createGrid(d.type);
    const std::uint64_t valueSize = rootValueSize(*empty);
    const bool boolValues = empty->valueType() == "bool";

    r.skip(sizeof(std::int32_t), "a tree's buffer count");
    r.skip(valueSize, "a tree's background value");
    if (boolValues) checkBool(r, r.offset() - valueSize, grid + "'s background value");
    const auto tiles = r.value<std::uint32_t>("a root node's tile count");
    const auto children = r.value<std::uint32_t>("a root node's child count");
    const std::uint64_t record = 3 * sizeof(std::int32_t) + valueSize + 1;
    if (std::uint64_t(tiles) * record > r.remaining()) {
        r.fail("is truncated or corrupt: " + grid + "'s root node at byte " + std::to_string(r.offset() - 8) +
               " claims " + std::to_string(tiles) + " tiles of " + std::to_string(record) + " bytes, the file has " +
               std::to_string(r.remaining()) + " bytes left");
    }
    for (std::uint32_t t = 0; t < tiles; ++t) {
        const std::string tile = grid + "'s root tile " + std::to_string(t);
        r.skip(3 * sizeof(std::int32_t) + valueSize + 1, "a root tile");
        if (boolValues) checkBool(r, r.offset() - 1 - valueSize, tile + " value");
        checkBool(r, r.offset() - 1, tile + " active flag");
    }
    if (tiles == 0 && children == 0) return true; // an empty tree: RootNode::readTopology stops here
    std::optional<ValueLayout> layout = valueLayout(d, valueSize);
    if (!layout) return false;
    layout->compression = compression;
    checkTree(r, *layout, children, grid);
    return true;
}

} // namespace

void preflightVdbFile(const std::filesystem::path& path)
{
    openvdb::initialize();
    Reader r(path);
    if (r.remaining() < 8 || r.value<std::int64_t>("the magic number") != openvdb::OPENVDB_MAGIC) {
        r.fail("is not a readable OpenVDB file (no VDB magic number)");
    }
    const auto version = r.value<std::uint32_t>("the file version");
    if (version < MIN_VDB_FILE_VERSION || version > openvdb::OPENVDB_FILE_VERSION) {
        r.fail("has format version " + std::to_string(version) + ": Strata reads versions " +
               std::to_string(MIN_VDB_FILE_VERSION) + " to " + std::to_string(openvdb::OPENVDB_FILE_VERSION) +
               " (OpenVDB 3.0 to " + std::to_string(openvdb::OPENVDB_LIBRARY_MAJOR_VERSION) + "." +
               std::to_string(openvdb::OPENVDB_LIBRARY_MINOR_VERSION) + ")");
    }
    r.skip(8, "the library version");
    const bool offsets = r.value<char>("the grid offsets flag") != 0;
    r.skip(36, "the file's UUID");
    checkMetadata(r, "the file's");
    const auto grids = r.value<std::int32_t>("the grid count");
    if (grids < 0 || std::uint64_t(grids) * 36 > r.remaining()) {
        r.fail("is truncated or corrupt: it claims " + std::to_string(grids) + " grids");
    }
    for (std::int32_t g = 0; g < grids; ++g) {
        const Descriptor d = checkDescriptor(r);
        // An instance has no blocks: OpenVDB leaves its block offset at 0.
        const bool ordered = d.instance ? d.endPos >= d.gridPos : d.blockPos >= d.gridPos && d.endPos >= d.blockPos;
        if (offsets && (d.gridPos != std::int64_t(d.end) || !ordered)) {
            r.fail("is corrupt: grid " + std::to_string(g) + "'s offsets (" + std::to_string(d.gridPos) + ", " +
                   std::to_string(d.blockPos) + ", " + std::to_string(d.endPos) + ") are out of order");
        }
        checkGrid(r, d, version, g);
        if (!offsets) return; // a stream: the grid's buffers follow, and their end is not recorded
        r.seek(std::uint64_t(d.endPos));
    }
}

std::optional<std::uint64_t> preflightVdbGrid(const std::filesystem::path& path, std::uint64_t offset,
                                              std::uint32_t fileVersion,
                      std::int32_t index)
{
    Reader r(path);
    r.seek(offset);
    const Descriptor d = checkDescriptor(r);
    if (!checkGrid(r, d, fileVersion, index)) return std::nullopt;
    return r.offset();
}

} // namespace strata::meshing::detail
