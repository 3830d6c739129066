// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/GridIO.h>

#include "VdbPreflight.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include <openvdb/io/Archive.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/io/io.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace strata::meshing {

namespace {

// OpenVDB stamps every file with a random UUID (at byte 21: after the magic
// number, the file and library versions and the grid-offsets flag), so two
// writes of the same grid differ. Replace it with a UUID derived from the
// rest of the file: the same grid gives the same bytes, and the UUID still
// identifies the content, which is what OpenVDB uses it for.
constexpr std::size_t UUID_OFFSET = 21;
constexpr std::size_t UUID_LENGTH = 36;

void makeUuidDeterministic(std::string& bytes)
{
    if (bytes.size() < UUID_OFFSET + UUID_LENGTH || bytes[UUID_OFFSET + 8] != '-' || bytes[UUID_OFFSET + 13] != '-' ||
        bytes[UUID_OFFSET + 18] != '-' || bytes[UUID_OFFSET + 23] != '-') {
        return; // an unknown header layout: leave the bytes as OpenVDB wrote them
    }
    // Two 64-bit FNV-1a hashes with different offsets: 128 bits of content hash.
    std::uint64_t h[2] = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull};
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        if (i == UUID_OFFSET) i += UUID_LENGTH;
        if (i >= bytes.size()) break;
        for (std::uint64_t& v : h) v = (v ^ std::uint8_t(bytes[i])) * 0x100000001b3ull;
    }
    char uuid[UUID_LENGTH + 1];
    std::snprintf(uuid, sizeof(uuid), "%08x-%04x-4%03x-%04x-%012llx", unsigned(h[0] >> 32), unsigned(h[0] >> 16) & 0xffffu,
                  unsigned(h[0]) & 0xfffu, unsigned((h[1] >> 48) & 0x3fffu) | 0x8000u,
                  static_cast<unsigned long long>(h[1] & 0xffffffffffffull));
    bytes.replace(UUID_OFFSET, UUID_LENGTH, uuid, UUID_LENGTH);
}

// io::Stream's reader, grid by grid (the same calls as its constructor in
// OpenVDB 10, without delayed loading), with each grid checked by
// preflightVdbGrid() at the byte where OpenVDB is about to read it, before
// OpenVDB parses it: what a grid holds is only known where the previous one
// ended, whatever the file's recorded offsets say.
class CheckedStreamReader : public openvdb::io::Archive
{
public:
    /// Reads every grid of `in`, the file at `path`; OpenVDB's exceptions
    /// and the stream's (failbit) pass through.
    VdbFile read(std::istream& in, const std::filesystem::path& path)
    {
        readHeader(in);
        auto streamMetadata = std::make_shared<openvdb::io::StreamMetadata>();
        openvdb::io::setStreamMetadataPtr(in, streamMetadata, /*transfer*/ false);
        openvdb::io::setVersion(in, libraryVersion(), fileVersion());
        openvdb::io::setDataCompression(in, compression());
        openvdb::MetaMap fileMetadata;
        fileMetadata.readMeta(in);
        const std::int32_t count = readGridCount(in);
        VdbFile file;
        file.grids = std::make_shared<openvdb::GridPtrVec>();
        std::vector<openvdb::io::GridDescriptor> descriptors;
        NamedGridMap named;
        std::set<openvdb::Name> skipped;
        for (std::int32_t i = 0; i < count; ++i) {
            const std::optional<std::uint64_t> end =
                detail::preflightVdbGrid(path, std::uint64_t(in.tellg()), fileVersion(), i);
            openvdb::io::GridDescriptor descriptor;
            const openvdb::GridBase::Ptr grid = descriptor.read(in); // throws for an unregistered type
            const bool parentSkipped =
                descriptor.isInstance() && skipped.count(openvdb::Name(descriptor.instanceParentName()));
            if (!end || parentSkipped) {
                // A tree the preflight cannot follow (bool, mask, points) or an
                // instance of one: jump over it, unread.
                skipGrid(in, descriptor, path, i);
                file.unread.push_back({descriptor.gridName(), descriptor.gridType()});
                skipped.insert(descriptor.uniqueName());
                continue;
            }
            Archive::readGrid(grid, descriptor, in);
            // The preflight followed the grid's bytes as OpenVDB reads them:
            // both must end at the same byte, or the checks were of other bytes.
            if (end && std::uint64_t(in.tellg()) != *end) {
                throw Error(ErrorKind::BadInput,
                            "VDB file '" + path.string() + "' is corrupt: grid " + std::to_string(i) +
                                " ends at byte " + std::to_string(std::uint64_t(in.tellg())) + ", not at byte " +
                                std::to_string(*end) + " where its nodes say",
                            {.file = path.string()});
            }
            file.grids->push_back(grid);
            named[descriptor.uniqueName()] = grid;
            descriptors.push_back(descriptor);
        }
        for (const openvdb::io::GridDescriptor& descriptor : descriptors) connectInstance(descriptor, named);
        openvdb::io::clearStreamMetadataPtr(in);
        file.version = version();
        return file;
    }

private:
    /// Moves `in` to the end of the grid whose descriptor was just read,
    /// through the offsets the file records (every file io::File writes
    /// has them; a stream has none, and then the grid cannot be skipped).
    void skipGrid(std::istream& in, const openvdb::io::GridDescriptor& descriptor,
                  const std::filesystem::path& path, std::int32_t index)
    {
        const std::string which = "grid " + std::to_string(index) + " ('" + descriptor.gridName() + "', " +
                                  descriptor.gridType() + ")";
        if (!inputHasGridOffsets()) {
            throw Error(ErrorKind::BadInput,
                        "VDB file '" + path.string() + "': " + which +
                            " is of a kind Strata does not read, and the file records no grid offsets to skip it",
                        {.file = path.string()});
        }
        const std::int64_t here = std::int64_t(in.tellg());
        in.seekg(0, std::ios::end);
        const std::int64_t size = std::int64_t(in.tellg());
        if (descriptor.getEndPos() < here || descriptor.getEndPos() > size) {
            throw Error(ErrorKind::BadInput,
                        "VDB file '" + path.string() + "' is corrupt: " + which + " ends at byte " +
                            std::to_string(descriptor.getEndPos()) + ", outside bytes " + std::to_string(here) +
                            " to " + std::to_string(size),
                        {.file = path.string()});
        }
        in.seekg(descriptor.getEndPos());
    }
};

// io::File writes through an std::ofstream whose state it never checks after
// writing; the archive's stream writer (what io::File calls, with seeking,
// so the bytes are the same) into memory lets us check every write ourselves.
class MemoryArchive : public openvdb::io::Archive
{
public:
    std::string bytes(const openvdb::GridCPtrVec& grids) const
    {
        std::ostringstream out(std::ios::out | std::ios::binary);
        write(out, grids, /*seekable*/ true);
        if (!out) throw std::runtime_error("the memory stream failed");
        return std::move(out).str();
    }
};

} // namespace

void writeGrid(const openvdb::FloatGrid& grid, const std::filesystem::path& path)
{
    openvdb::initialize();
    std::string bytes;
    try {
        openvdb::GridCPtrVec grids;
        // The copy shares the tree (no deep copy).
        grids.push_back(grid.copy());
        bytes = MemoryArchive().bytes(grids);
    } catch (const std::exception& e) {
        throw Error(ErrorKind::Internal, "cannot write VDB file '" + path.string() + "': " + e.what(), {.file = path.string()});
    }
    makeUuidDeterministic(bytes);
    writeFileAtomically(path, bytes);
}

VdbFile readVdbFile(const std::filesystem::path& path)
{
    openvdb::initialize();
    const std::string where = "VDB file '" + path.string() + "'";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        throw Error(ErrorKind::BadInput, where + " does not exist");
    }
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw Error(ErrorKind::BadInput, where + " is not a file");
    }
    // Lengths, counts and offsets that OpenVDB would trust, checked first.
    detail::preflightVdbFile(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error(ErrorKind::Io, where + " cannot be opened: " + std::strerror(errno), {.file = path.string()});
    }
    VdbFile file;
    try {
        // Read as a stream: every grid in full, in file order. OpenVDB does
        // not check its reads, and after a short read it would go on with
        // whatever its variables held (reading a truncated file then
        // allocated gigabytes): the stream throws at the first short read.
        in.exceptions(std::ios::failbit | std::ios::badbit);
        file = CheckedStreamReader().read(in, path);
    } catch (const Error&) {
        throw; // the preflight's, naming the byte
    } catch (const std::ios_base::failure&) {
        throw Error(ErrorKind::BadInput, where + " is truncated or corrupt: it ends before its last grid does");
    } catch (const std::exception& e) {
        throw Error(ErrorKind::BadInput, where + " is not a readable OpenVDB file: " + e.what());
    }
    if (!file.grids) file.grids = std::make_shared<openvdb::GridPtrVec>();
    return file;
}

openvdb::FloatGrid::Ptr readLevelSet(const std::filesystem::path& path)
{
    const std::string where = "VDB file '" + path.string() + "'";
    const VdbFile file = readVdbFile(path);
    const openvdb::GridPtrVecPtr& grids = file.grids;
    if (!grids || grids->empty()) {
        if (!file.unread.empty()) {
            throw Error(ErrorKind::BadInput, where + " holds no float grid (found '" + file.unread.front().type + "', not read)");
        }
        throw Error(ErrorKind::BadInput, where + " holds no grid");
    }
    openvdb::FloatGrid::Ptr grid;
    for (const openvdb::GridBase::Ptr& base : *grids) {
        if ((grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base))) break;
    }
    if (!grid) {
        throw Error(ErrorKind::BadInput, where + " holds no float grid (found '" + grids->front()->type() + "')");
    }
    if (grid->getGridClass() != openvdb::GRID_LEVEL_SET) {
        throw Error(ErrorKind::BadInput, where + ": grid '" + grid->getName() + "' is not a level set (class '" +
                    openvdb::GridBase::gridClassToString(grid->getGridClass()) + "')");
    }
    if (!grid->hasUniformVoxels() || !grid->transform().isLinear()) {
        throw Error(ErrorKind::BadInput, where + ": grid '" + grid->getName() + "' needs a linear transform with cubic voxels");
    }
    if (grid->activeVoxelCount() == 0) {
        throw Error(ErrorKind::BadInput, where + ": grid '" + grid->getName() + "' is empty (no active voxels)");
    }
    return grid;
}

} // namespace strata::meshing
