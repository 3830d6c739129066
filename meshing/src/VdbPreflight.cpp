#include "VdbPreflight.h"

#include <strata/Error.h>

#include <openvdb/Metadata.h>
#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/openvdb.h>

#include <cstdint>
#include <cstring>
#include <fstream>
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
            if (size >= 4) {
                const std::uint64_t start = r.offset();
                const auto masks = r.value<std::uint32_t>("a delayed-load mask count");
                if (std::uint64_t(masks) > 64 * std::uint64_t(size)) {
                    r.fail("is corrupt: metadata '" + name + "' at byte " + std::to_string(start) + " claims " +
                           std::to_string(masks) + " masks in " + std::to_string(size) + " bytes");
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
        r.string("a grid name");
        r.string("a grid type");
        r.string("an instance parent name");
        const auto gridPos = r.value<std::int64_t>("a grid offset");
        const auto blockPos = r.value<std::int64_t>("a grid offset");
        const auto endPos = r.value<std::int64_t>("a grid offset");
        if (offsets && (gridPos != std::int64_t(r.offset()) || blockPos < gridPos || endPos < blockPos)) {
            r.fail("is corrupt: grid " + std::to_string(g) + "'s offsets (" + std::to_string(gridPos) + ", " +
                   std::to_string(blockPos) + ", " + std::to_string(endPos) + ") are out of order");
        }
        r.skip(4, "a grid's compression flags");
        checkMetadata(r, "a grid's");
        r.string("a transform type");
        if (!offsets) return; // a stream: the tree follows, and its end is not recorded
        r.seek(std::uint64_t(endPos));
    }
}

} // namespace strata::meshing::detail
