// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// A read-only HTTP server for one folder (a bake: tileset.json, tiles/,
/// viewer/), on cpp-httplib. GET and HEAD only (others: 405); files only
/// from inside the folder (RequestPath.h checks the path; the file is then
/// opened relative to the folder's descriptor with openat2(RESOLVE_BENEATH |
/// RESOLVE_NO_SYMLINKS), so a link swapped in after the check is not
/// followed); Content-Type from the extension (MimeType.h); byte ranges on
/// GET (206 with Content-Range, several ranges as multipart/byteranges, 416
/// with `Content-Range: bytes *\/SIZE` when none is satisfiable; a HEAD
/// ignores Range); gzip (never brotli: at the quality httplib uses it takes
/// a second for a large script) when the client's Accept-Encoding asks and
/// options.compression covers the type (never for a range, never for
/// PNG/JPEG/KTX2 or an unknown extension), the gzipped body kept in a cache
/// bounded in bytes for the next request of the same version of the file;
/// a HEAD never compresses (without a cached body it has no
/// Content-Length). Each file has an ETag (size and modification time):
/// If-None-Match gives 304, an If-Range that does not match sends the whole
/// file. A folder serves its index.html, or 404: there is no listing.
///
/// Usage: construct (binds the port), print url(), run() on one thread,
/// stop() from another (a signal watcher).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace strata::serve {

/// Which files are gzipped when the client accepts it.
enum class Compression
{
    None, ///< nothing: every file as it is
    Text, ///< text, JSON and glTF JSON (Compressibility::Text): on the loopback, where
          ///< sending a binary tile as it is costs less than compressing it
    All,  ///< also binary glTF, .bin and WebAssembly (Compressibility::Binary): for a network.
          ///< Never an unknown extension (compressibilityFor()), nor PNG/JPEG/KTX2
    Auto, ///< per request, by the client's address: Text for a client on the loopback, All
          ///< for any other (a server on 0.0.0.0 serves both)
};

/// A loopback address: "localhost", 127.0.0.0/8, ::1, or an IPv4 one
/// mapped into IPv6 (::ffff:127.x.y.z). For the address to listen on and
/// the peer's alike.
bool isLoopbackAddress(std::string_view address);

/// What `compression` means for a request from `clientAddress` (the peer's
/// numeric address): Auto becomes Text for a loopback client
/// (isLoopbackAddress()) and All for any other; the others stay.
Compression compressionFor(Compression compression, std::string_view clientAddress);

/// One answered request, for a log.
struct RequestRecord
{
    std::string method;  ///< "GET", "HEAD", ... (others were answered 405)
    std::string target;  ///< as the client sent it (percent-encoded, with the query)
    int status = 0;      ///< the HTTP status sent
    std::uint64_t bytes = 0; ///< the Content-Length sent (compressed size when compressed; for HEAD, a GET's,
                             ///< or 0 for a gzipped answer whose body is not cached)
};

struct FileServerOptions
{
    /// The address to listen on: 127.0.0.1 keeps the folder on this machine;
    /// 0.0.0.0 or :: serves it to the network.
    std::string host = "127.0.0.1";
    /// The TCP port; 0 picks a free one (port() says which).
    int port = 8080;
    /// Worker threads, one per open connection (a browser opens six).
    std::size_t threads = 16;
    /// What is compressed (never a range, never PNG/JPEG/KTX2).
    Compression compression = Compression::Text;
    /// zlib level of on-the-fly gzip, 1 (fastest, nginx's default) to 9.
    int gzipLevel = 1;
    /// Called after each answer, on the worker thread that answered it
    /// (several at once: synchronise inside); null: no log.
    std::function<void(const RequestRecord&)> onRequest{};
    /// Files larger than this are never compressed (they would be held in
    /// memory whole); they are streamed as they are. Also the most bytes
    /// that several ranges of one file are answered with as multipart.
    std::size_t maxCompressedFileBytes = std::size_t(64) << 20;
    /// The gzipped bodies kept for the next request of the same version of
    /// the same file (device, inode, size, modification time), in bytes of
    /// gzip, least recently used dropped first; a body larger than this is
    /// sent but not kept; 0 keeps none (every GET compresses again).
    std::size_t compressedCacheBytes = std::size_t(64) << 20;
};

/// What the server did since it was constructed (for a log or monitoring).
struct FileServerStats
{
    std::uint64_t compressions = 0;     ///< files read and gzipped (a GET that found no cached body)
    std::uint64_t compressedHits = 0;   ///< GETs and HEADs answered with a cached gzipped body
    std::size_t compressedCacheBytes = 0; ///< what the cache of gzipped bodies holds now
};

class FileServer
{
public:
    /// Binds `options.host:options.port` for `root`. Throws strata::Error:
    /// BadInput when `root` is not a folder or the port is not in
    /// [0, 65535]; Io when the address cannot be bound (the port is in use,
    /// the host is not an address of this machine), naming host and port.
    explicit FileServer(const std::filesystem::path& root, const FileServerOptions& options = {});
    /// Stops the server if it runs (run() must have returned before the
    /// destructor runs, i.e. join the thread that called it).
    ~FileServer();
    FileServer(const FileServer&) = delete;
    FileServer& operator=(const FileServer&) = delete;

    /// The bound port (the free one chosen for port 0).
    int port() const;
    /// The address it listens on, as given.
    const std::string& host() const;
    /// "http://HOST:PORT/" (IPv6 hosts in brackets).
    std::string url() const;
    /// The served folder, canonical.
    const std::filesystem::path& root() const;
    /// Counters since construction; callable from any thread.
    FileServerStats stats() const;

    /// Serves requests until stop(); returns once the listening socket is
    /// closed and every connection has finished. Call once. Throws
    /// strata::Error (Io) when accepting connections fails.
    void run();
    /// Asks run() to return; callable from any thread, before, during or
    /// after run(), any number of times. Not async-signal-safe: call it from
    /// a thread that waited for the signal (sigwait), not from a handler.
    void stop();

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

} // namespace strata::serve
