// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// What the serve tests share: raw HTTP over a socket (for request lines an
// HTTP client would normalise), gunzip, whole files.

#include <gtest/gtest.h>

#include <zlib.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace strata::test {

struct RawResponse
{
    int status = 0;       // 0: no status line came back
    std::string head;     // status line and headers
    std::string body;
};

/// Sends `request` as it is to 127.0.0.1:`port` and reads until the server
/// closes the connection (ask for it with `Connection: close`) or 5 s pass.
inline RawResponse rawRequest(int port, const std::string& request)
{
    RawResponse out;
    const int sock = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(std::uint16_t(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
        ::close(sock);
        return out;
    }
    std::size_t sent = 0;
    while (sent < request.size()) {
        const ssize_t n = ::send(sock, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) break;
        sent += std::size_t(n);
    }
    std::string all;
    char buffer[65536];
    pollfd waiting{sock, POLLIN, 0};
    while (::poll(&waiting, 1, 5000) > 0) {
        const ssize_t n = ::recv(sock, buffer, sizeof(buffer), 0);
        if (n <= 0) break;
        all.append(buffer, std::size_t(n));
    }
    ::close(sock);
    const std::size_t end = all.find("\r\n\r\n");
    out.head = all.substr(0, end);
    if (end != std::string::npos) out.body = all.substr(end + 4);
    if (all.starts_with("HTTP/1.1 ") && all.size() >= 12) out.status = std::stoi(all.substr(9, 3));
    return out;
}

/// A gzip member (or several) decompressed; throws on a corrupt stream.
inline std::string gunzip(const std::string& data)
{
    z_stream stream{};
    if (inflateInit2(&stream, 15 + 16) != Z_OK) throw std::runtime_error("inflateInit2 failed");
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    stream.avail_in = uInt(data.size());
    std::string out;
    char buffer[65536];
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        stream.next_out = reinterpret_cast<Bytef*>(buffer);
        stream.avail_out = sizeof(buffer);
        rc = inflate(&stream, Z_NO_FLUSH);
        if (rc != Z_OK && rc != Z_STREAM_END) {
            inflateEnd(&stream);
            throw std::runtime_error("not a gzip stream (inflate " + std::to_string(rc) + ")");
        }
        out.append(buffer, sizeof(buffer) - stream.avail_out);
    }
    inflateEnd(&stream);
    return out;
}

inline std::string readFile(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline void writeFile(const std::filesystem::path& path, const std::string& bytes)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

} // namespace strata::test
