// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The one translation unit that includes cpp-httplib (Debian builds it as a
// shared library, libcpp-httplib.so, with zlib, brotli and OpenSSL; its
// pkg-config file gives the matching CPPHTTPLIB_*_SUPPORT defines).

#include <strata/serve/FileServer.h>

#include "ByteRanges.h"
#include "CompressedBodyCache.h"
#include "Gzip.h"
#include "OpenBeneath.h"

#include <strata/Error.h>
#include <strata/detail/IntegerHash.h>
#include <strata/serve/MimeType.h>
#include <strata/serve/RequestPath.h>

#include <httplib.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <initializer_list>
#include <cstring>
#include <mutex>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

namespace strata::serve {

namespace {

namespace fs = std::filesystem;

// More ranges than this in one request are ignored (the whole file is
// sent, as RFC 9110 allows): many small overlapping ranges would make a
// tiny request cost a large multipart answer.
constexpr std::size_t MAX_RANGES = 16;

// httplib::Server with one addition: closing a socket that was bound but
// never listened on (httplib closes it only when listen() ends).
class HttpServer : public httplib::Server
{
public:
    void closeUnlistenedSocket()
    {
        const socket_t sock = svr_sock_.exchange(INVALID_SOCKET);
        if (sock != INVALID_SOCKET) ::close(sock);
    }
};

// An open file shared by the content provider's calls; closed with the last one.
struct OpenFile
{
    int fd = -1;
    ~OpenFile()
    {
        if (fd >= 0) ::close(fd);
    }
};

// cpp-httplib hands handlers the request as const, but it is a local,
// non-const object of the connection loop (Server::process_request), and
// apply_ranges() reads its `ranges` after the handler returns. Replacing
// them with the validated ones (or none) is how a handler says which bytes
// go out; see ByteRanges.h for why httplib's own slicing cannot be trusted.
httplib::Ranges& rangesToSend(const httplib::Request& request)
{
    return const_cast<httplib::Request&>(request).ranges;
}

// A short text answer for an error status, with any Range dropped (httplib
// would otherwise slice the error text).
void answer(const httplib::Request& request, httplib::Response& response, int status, const std::string& text)
{
    rangesToSend(request).clear();
    response.status = status;
    response.set_content(text + "\n", "text/plain; charset=utf-8");
}

// Accept-Encoding names `coding` with a q-value above 0 (RFC 9110 12.5.3).
bool accepts(const httplib::Request& request, std::string_view coding)
{
    const std::string header = request.get_header_value("Accept-Encoding");
    std::size_t start = 0;
    while (start < header.size()) {
        std::size_t end = header.find(',', start);
        if (end == std::string::npos) end = header.size();
        std::string token = header.substr(start, end - start);
        start = end + 1;
        std::string params;
        if (const std::size_t semi = token.find(';'); semi != std::string::npos) {
            params = token.substr(semi + 1);
            token.resize(semi);
        }
        token.erase(std::remove_if(token.begin(), token.end(), [](unsigned char c) { return std::isspace(c); }),
                    token.end());
        std::transform(token.begin(), token.end(), token.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (token != coding) continue;
        params.erase(std::remove_if(params.begin(), params.end(), [](unsigned char c) { return std::isspace(c); }),
                     params.end());
        if (params.starts_with("q=") || params.starts_with("Q=")) {
            const std::string q = params.substr(2);
            if (!q.empty() && std::strtod(q.c_str(), nullptr) <= 0.0) return false;
        }
        return true;
    }
    return false;
}

std::uint64_t modifiedNs(const timespec& modified)
{
    return std::uint64_t(modified.tv_sec) * 1000000000ULL + std::uint64_t(modified.tv_nsec);
}

// A strong entity tag from size and modification time (nanoseconds), with
// "-z" for the compressed representation.
std::string entityTag(std::uint64_t size, const timespec& modified, bool compressed)
{
    char text[80];
    std::snprintf(text, sizeof(text), "\"%llx-%llx%s\"", static_cast<unsigned long long>(size),
                  static_cast<unsigned long long>(modifiedNs(modified)), compressed ? "-z" : "");
    return text;
}

// An If-None-Match list names one of `tags` (weak comparison: W/ ignored)
// or is "*".
bool matchesAny(const std::string& header, std::initializer_list<std::string> tags)
{
    std::size_t start = 0;
    while (start < header.size()) {
        std::size_t end = header.find(',', start);
        if (end == std::string::npos) end = header.size();
        std::string tag = header.substr(start, end - start);
        start = end + 1;
        tag.erase(0, tag.find_first_not_of(" \t"));
        tag.erase(tag.find_last_not_of(" \t") + 1);
        if (tag.starts_with("W/")) tag.erase(0, 2);
        if (tag == "*") return true;
        for (const std::string& candidate : tags) {
            if (tag == candidate) return true;
        }
    }
    return false;
}

/// Bytes [offset, offset + length) of the file.
std::string readRange(int fd, std::uint64_t offset, std::uint64_t length)
{
    std::string data(length, '\0');
    std::uint64_t done = 0;
    while (done < length) {
        const ssize_t n = ::pread(fd, data.data() + done, length - done, off_t(offset + done));
        if (n <= 0) throw Error(ErrorKind::Io, std::string("read failed: ") + (n < 0 ? std::strerror(errno) : "file shrank"));
        done += std::uint64_t(n);
    }
    return data;
}

std::string readWhole(int fd, std::uint64_t size) { return readRange(fd, 0, size); }

/// A multipart/byteranges body (RFC 9110 14.6) of `ranges` of the file,
/// reading only those bytes. cpp-httplib 0.11 would write each part's
/// Content-Range total from the body's size (0 for a streamed file), so
/// the parts are made here and httplib is given no ranges.
std::string multipartBody(int fd, std::uint64_t size, const std::vector<detail::ByteRange>& ranges,
                          const std::string& mimeType, const std::string& boundary)
{
    std::string body;
    for (const auto& [first, last] : ranges) {
        body += "--" + boundary + "\r\nContent-Type: " + mimeType + "\r\nContent-Range: bytes " +
                std::to_string(first) + "-" + std::to_string(last) + "/" + std::to_string(size) + "\r\n\r\n";
        body += readRange(fd, std::uint64_t(first), std::uint64_t(last - first + 1));
        body += "\r\n";
    }
    body += "--" + boundary + "--\r\n";
    return body;
}

} // namespace

bool isLoopbackAddress(std::string_view address)
{
    if (address.starts_with("::ffff:")) address.remove_prefix(7); // IPv4 on an IPv6 socket
    return address == "localhost" || address == "::1" || address.starts_with("127.");
}

Compression compressionFor(Compression compression, std::string_view clientAddress)
{
    if (compression != Compression::Auto) return compression;
    // On the loopback bandwidth is memory bandwidth (a 0.9 MB tile: 3400
    // requests/s as it is, 58 gzipped), so only text is worth compressing.
    return isLoopbackAddress(clientAddress) ? Compression::Text : Compression::All;
}

struct FileServer::Impl
{
    fs::path root;
    // The root, opened once: every file is opened relative to it and beneath
    // it (OpenBeneath.h), whatever its path names later.
    int rootFd = -1;
    FileServerOptions options;
    int port = 0;
    HttpServer server;
    std::unique_ptr<detail::CompressedBodyCache> compressedBodies;
    std::atomic<std::uint64_t> compressions{0};
    std::atomic<std::uint64_t> compressedHits{0};

    std::mutex mutex; // guards the three flags
    bool listening = false;
    bool stopRequested = false;
    bool ran = false;

    ~Impl()
    {
        if (rootFd >= 0) ::close(rootFd);
    }

    void handle(const httplib::Request& request, httplib::Response& response);
};

void FileServer::Impl::handle(const httplib::Request& request, httplib::Response& response)
{
    const ResolvedPath resolved = resolveRequestPath(root, request.path);
    switch (resolved.status) {
    case 200: break;
    case 301: {
        rangesToSend(request).clear();
        // The path as the client wrote it (still percent-encoded), with one
        // leading slash: "//host/x" would be a link to another host.
        std::string target = request.target.substr(0, request.target.find('?'));
        target.erase(0, target.find_first_not_of('/'));
        response.set_redirect("/" + target + "/", 301);
        return;
    }
    case 400: answer(request, response, 400, "400 bad request path"); return;
    case 403: answer(request, response, 403, "403 forbidden: outside the served folder"); return;
    default: answer(request, response, 404, "404 not found"); return;
    }

    // Opened beneath the root, following no link: a folder of the checked
    // path swapped for a link since the check makes this fail (404), not
    // lead out of the folder.
    auto file = std::make_shared<OpenFile>();
    file->fd = detail::openBeneath(rootFd, resolved.file.lexically_relative(root));
    struct stat info{};
    if (file->fd < 0 || ::fstat(file->fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        answer(request, response, 404, "404 not found");
        return;
    }
    const auto size = std::uint64_t(info.st_size);
    const std::string mimeType(mimeTypeFor(resolved.file));
    const Compressibility kind = compressibilityFor(resolved.file);
    const Compression compression = compressionFor(options.compression, request.remote_addr);
    const bool compressible = (kind == Compressibility::Text && compression != Compression::None) ||
                              (kind == Compressibility::Binary && compression == Compression::All);
    response.set_header("Accept-Ranges", "bytes");
    response.set_header("Cache-Control", "no-cache"); // revalidate with the ETag: a re-bake replaces tiles in place
    response.set_header("X-Content-Type-Options", "nosniff");
    if (compressible) response.set_header("Vary", "Accept-Encoding");

    httplib::Ranges& ranges = rangesToSend(request);
    if (ranges.size() > MAX_RANGES) ranges.clear();
    // Range is defined for GET only (RFC 9110 14.2): a HEAD gets the headers
    // of the whole file, and never makes the multipart case below read it.
    if (request.method == "HEAD") ranges.clear();
    // The validator: size and modification time, which a re-bake's atomic
    // replace changes; the gzipped representation has its own.
    const std::string etag = entityTag(size, info.st_mtim, false);
    const std::string etagCompressed = entityTag(size, info.st_mtim, true);
    if (request.has_header("If-Range") && request.get_header_value("If-Range") != etag) {
        ranges.clear(); // the client's part is of another version (or a date, which is not checked): send it whole
    }
    const bool compressWhole =
        ranges.empty() && size > 0 && compressible && size <= options.maxCompressedFileBytes && accepts(request, "gzip");
    response.set_header("ETag", compressWhole ? etagCompressed : etag);
    if (matchesAny(request.get_header_value("If-None-Match"), {etag, etagCompressed})) {
        ranges.clear();
        response.status = 304;
        return;
    }

    if (!ranges.empty()) {
        std::vector<detail::ByteRange> requested(ranges.begin(), ranges.end());
        const std::vector<detail::ByteRange> satisfiable = detail::satisfiableRanges(requested, size);
        if (satisfiable.empty()) {
            answer(request, response, 416, "416 range not satisfiable");
            response.set_header("Content-Range", "bytes */" + std::to_string(size));
            return;
        }
        ranges.assign(satisfiable.begin(), satisfiable.end());
        if (ranges.size() > 1) {
            // Several ranges: a multipart body of just those bytes. Ranges
            // that add up past the file (overlaps) or past the in-memory
            // cap are answered with the whole file, streamed, as RFC 9110
            // allows: a small request must not cost a large answer.
            std::uint64_t bytes = 0;
            for (const auto& [first, last] : satisfiable) bytes += std::uint64_t(last - first + 1);
            ranges.clear(); // httplib must not slice what is sent
            if (bytes <= size && bytes <= options.maxCompressedFileBytes) {
                // A boundary no part can hold by chance: 128 bits from this
                // version of the file.
                const std::uint64_t a = strata::detail::mix64(std::uint64_t(info.st_ino) ^ (size << 1));
                const std::uint64_t b = strata::detail::mix64(std::uint64_t(modifiedNs(info.st_mtim)) + a);
                char boundary[48];
                std::snprintf(boundary, sizeof boundary, "strata-%016llx%016llx", static_cast<unsigned long long>(a),
                              static_cast<unsigned long long>(b));
                response.status = 206;
                response.set_content(multipartBody(file->fd, size, satisfiable, mimeType, boundary),
                                     "multipart/byteranges; boundary=" + std::string(boundary));
                return;
            }
        }
    } else if (size == 0) {
        response.set_content("", mimeType);
        return;
    } else if (compressWhole) {
        // Whole and compressible: gzipped here, kept in the cache for the
        // next request of this version, and handed over as a sized provider,
        // which httplib sends as it is. (Given the bytes, httplib 0.11
        // compresses text itself, with brotli at quality 11 whenever the
        // client accepts br, as browsers do: 0.95 s for the viewer's 880 KB
        // script and 0.65 s for a 4 km world's tileset.json, against 8 and
        // 3 ms for gzip; that was half of the viewer's first frame.)
        response.set_header("Content-Encoding", "gzip");
        const detail::CompressedBodyKey key{std::uint64_t(info.st_dev), std::uint64_t(info.st_ino), size,
                                            modifiedNs(info.st_mtim), options.gzipLevel};
        std::shared_ptr<const std::string> zipped = compressedBodies->find(key);
        if (zipped) {
            ++compressedHits;
        } else if (request.method == "HEAD") {
            // The headers only: no file is read and compressed for a length
            // nobody will download (the post-routing handler drops the
            // Content-Length: 0 httplib adds to an answer without a body).
            response.status = 200;
            response.set_header("Content-Type", mimeType);
            return;
        } else {
            ++compressions;
            zipped = std::make_shared<const std::string>(detail::gzipCompress(readWhole(file->fd, size), options.gzipLevel));
            // Kept only if the file did not change while it was read (a torn
            // body under this version's key would be served until it changes
            // again).
            struct stat after{};
            if (::fstat(file->fd, &after) == 0 && std::uint64_t(after.st_size) == size &&
                modifiedNs(after.st_mtim) == key.modifiedNs) {
                zipped = compressedBodies->insert(key, zipped);
            }
        }
        response.set_content_provider(
            zipped->size(), mimeType, [zipped](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                return sink.write(zipped->data() + offset, std::min(length, zipped->size() - offset));
            });
        return;
    }

    // Streamed from the file: the whole of it, or the ranges (httplib writes
    // 206, Content-Range, or multipart/byteranges for several).
    response.set_content_provider(
        size, mimeType, [file](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
            std::array<char, 64 * 1024> buffer;
            const ssize_t n = ::pread(file->fd, buffer.data(), std::min(length, buffer.size()), off_t(offset));
            if (n <= 0) return false; // an error or a file that shrank: httplib drops the connection
            return sink.write(buffer.data(), std::size_t(n));
        });
}

FileServer::FileServer(const fs::path& root, const FileServerOptions& options) : mImpl(std::make_unique<Impl>())
{
    std::error_code ec;
    if (!fs::is_directory(root, ec)) {
        throw Error(ErrorKind::BadInput, "serve: '" + root.string() + "' is not a folder", ErrorPlace{root.string()});
    }
    if (options.port < 0 || options.port > 65535) {
        throw Error(ErrorKind::BadInput, "serve: port " + std::to_string(options.port) + " is not in [0, 65535]",
                    ErrorPlace{"", 0, "--port", std::to_string(options.port)});
    }
    if (options.gzipLevel < 1 || options.gzipLevel > 9) {
        throw Error(ErrorKind::BadInput, "serve: gzip level " + std::to_string(options.gzipLevel) + " is not in [1, 9]");
    }
    mImpl->root = fs::canonical(root);
    mImpl->rootFd = ::open(mImpl->root.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (mImpl->rootFd < 0) {
        throw Error(ErrorKind::Io, "serve: cannot open '" + root.string() + "': " + std::strerror(errno),
                    ErrorPlace{root.string()});
    }
    mImpl->compressedBodies = std::make_unique<detail::CompressedBodyCache>(options.compressedCacheBytes);
    mImpl->options = options;

    HttpServer& server = mImpl->server;
    Impl* impl = mImpl.get();
    server.set_keep_alive_max_count(1000); // a viewer fetches thousands of tiles over a few connections
    // An idle connection is closed after 2 s (httplib: 5 s): stop() waits
    // for it, and a new connection costs little on the loopback.
    server.set_keep_alive_timeout(2);
    // TCP_NODELAY: without it a small file (a 20 kB tileset.json) took
    // 44 ms a request on the loopback, headers and body waiting on
    // Nagle's algorithm and the client's delayed ACK (23 requests/s).
    server.set_tcp_nodelay(true);
    // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a
    // second server binds the same port and the kernel splits the requests
    // between the two; a port in use must be an error instead.
    server.set_socket_options([](socket_t sock) {
        int yes = 1;
        ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    server.set_payload_max_length(64 * 1024); // nothing is uploaded
    server.set_pre_routing_handler([](const httplib::Request& request, httplib::Response& response) {
        if (request.method == "GET" || request.method == "HEAD") return httplib::Server::HandlerResponse::Unhandled;
        answer(request, response, 405, "405 method not allowed: this server is read-only (GET, HEAD)");
        response.set_header("Allow", "GET, HEAD");
        return httplib::Server::HandlerResponse::Handled;
    });
    // A HEAD of a gzipped answer whose body is not cached has no length to
    // give; httplib writes "Content-Length: 0" for an answer without a body.
    // Drop it (a gzip body is never empty, so 0 is never its real length).
    server.set_post_routing_handler([](const httplib::Request& request, httplib::Response& response) {
        if (request.method == "HEAD" && response.get_header_value("Content-Encoding") == "gzip" &&
            response.get_header_value("Content-Length") == "0") {
            response.headers.erase("Content-Length");
        }
    });
    if (options.onRequest) {
        server.set_logger([impl](const httplib::Request& request, const httplib::Response& response) {
            RequestRecord record{request.method, request.target, response.status, 0};
            const std::string length = response.get_header_value("Content-Length");
            if (!length.empty()) record.bytes = std::strtoull(length.c_str(), nullptr, 10);
            impl->options.onRequest(record);
        });
    }
    // HEAD is answered by the GET handler; httplib sends the headers only.
    server.Get(".*", [impl](const httplib::Request& request, httplib::Response& response) {
        impl->handle(request, response);
    });
    // Called by listen() once it runs: from here on stop() can close the
    // socket; a stop() that came earlier is honoured now.
    server.new_task_queue = [impl] {
        std::lock_guard lock(impl->mutex);
        impl->listening = true;
        if (impl->stopRequested) impl->server.stop();
        return new httplib::ThreadPool(std::max<std::size_t>(1, impl->options.threads));
    };

    errno = 0;
    const std::string address = options.host + ":" + std::to_string(options.port);
    if (options.port == 0) {
        mImpl->port = server.bind_to_any_port(options.host);
    } else {
        mImpl->port = server.bind_to_port(options.host, options.port) ? options.port : -1;
    }
    if (mImpl->port <= 0) {
        const int error = errno;
        std::string why = error == EADDRINUSE ? "the port is in use (another server? --port 0 picks a free one)"
                          : error != 0       ? std::strerror(error)
                                             : "the host is not a name or address of this machine";
        throw Error(ErrorKind::Io, "serve: cannot listen on " + address + ": " + why,
                    ErrorPlace{"", 0, "--port", std::to_string(options.port)});
    }
}

FileServer::~FileServer()
{
    stop();
    std::lock_guard lock(mImpl->mutex);
    if (!mImpl->listening) mImpl->server.closeUnlistenedSocket();
}

int FileServer::port() const { return mImpl->port; }

const std::string& FileServer::host() const { return mImpl->options.host; }

std::string FileServer::url() const
{
    const std::string& host = mImpl->options.host;
    const bool ipv6 = host.find(':') != std::string::npos;
    return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(mImpl->port) + "/";
}

const fs::path& FileServer::root() const { return mImpl->root; }

FileServerStats FileServer::stats() const
{
    return {mImpl->compressions.load(), mImpl->compressedHits.load(), mImpl->compressedBodies->bytes()};
}

void FileServer::run()
{
    {
        std::lock_guard lock(mImpl->mutex);
        if (mImpl->ran) throw Error(ErrorKind::Internal, "serve: FileServer::run() called twice");
        mImpl->ran = true;
    }
    errno = 0;
    if (!mImpl->server.listen_after_bind()) {
        const int error = errno;
        throw Error(ErrorKind::Io, "serve: accepting connections on " + url() + " failed" +
                                       (error ? std::string(": ") + std::strerror(error) : std::string()));
    }
}

void FileServer::stop()
{
    std::lock_guard lock(mImpl->mutex);
    mImpl->stopRequested = true;
    if (mImpl->listening) mImpl->server.stop(); // no-op once stopped
}

} // namespace strata::serve
