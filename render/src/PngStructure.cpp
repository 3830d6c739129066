#include <strata/render/PngStructure.h>

#include <strata/Error.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace strata::render {

void checkPngStructure(const std::filesystem::path& path)
{
    static const unsigned char SIGNATURE[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return; // the reader reports it
    std::ifstream in(path, std::ios::binary);
    unsigned char header[8];
    if (size < 8 || !in.read(reinterpret_cast<char*>(header), 8) || std::memcmp(header, SIGNATURE, 8) != 0) return;
    std::uint64_t offset = 8;
    for (;;) {
        if (size - offset < 12) {
            throw Error("is a truncated PNG: it ends at byte " + std::to_string(size) + " without an IEND chunk");
        }
        unsigned char chunk[8];
        in.seekg(std::streamoff(offset));
        if (!in.read(reinterpret_cast<char*>(chunk), 8)) throw Error("cannot be read at byte " + std::to_string(offset));
        const std::uint64_t length = (std::uint64_t(chunk[0]) << 24) | (std::uint64_t(chunk[1]) << 16) |
                                     (std::uint64_t(chunk[2]) << 8) | std::uint64_t(chunk[3]);
        std::string type(reinterpret_cast<const char*>(chunk + 4), 4);
        for (char& c : type) {
            if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) c = '?';
        }
        if (length > 0x7fffffffu || length + 12 > size - offset) {
            throw Error("is a truncated PNG: chunk '" + type + "' at byte " + std::to_string(offset) + " needs " +
                        std::to_string(length + 12) + " bytes, the file has " + std::to_string(size - offset) + " left");
        }
        offset += length + 12;
        if (type == "IEND") return;
    }
}

} // namespace strata::render
