// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Sha256.h>

#include <strata/Error.h>

#include <openssl/evp.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>

namespace strata {

namespace {

class Digest
{
public:
    Digest()
        : mContext(EVP_MD_CTX_new(), EVP_MD_CTX_free)
    {
        if (!mContext || EVP_DigestInit_ex(mContext.get(), EVP_sha256(), nullptr) != 1)
            throw Error(ErrorKind::Internal, "SHA-256: libcrypto could not start a digest");
    }

    void update(const void* data, std::size_t size)
    {
        if (EVP_DigestUpdate(mContext.get(), data, size) != 1)
            throw Error(ErrorKind::Internal, "SHA-256: libcrypto failed");
    }

    std::string hex()
    {
        std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
        unsigned int size = 0;
        if (EVP_DigestFinal_ex(mContext.get(), digest.data(), &size) != 1)
            throw Error(ErrorKind::Internal, "SHA-256: libcrypto failed");
        static const char* DIGITS = "0123456789abcdef";
        std::string out;
        for (unsigned int i = 0; i < size; ++i) {
            out.push_back(DIGITS[digest[i] >> 4]);
            out.push_back(DIGITS[digest[i] & 15]);
        }
        return out;
    }

private:
    std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> mContext;
};

} // namespace

std::string sha256Hex(std::string_view bytes)
{
    Digest digest;
    digest.update(bytes.data(), bytes.size());
    return digest.hex();
}

std::string sha256File(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::Io, "cannot read '" + path.string() + "': " + std::strerror(errno), {path.string()});
    Digest digest;
    std::array<char, 1 << 16> block;
    while (in) {
        in.read(block.data(), block.size());
        if (in.gcount() > 0) digest.update(block.data(), std::size_t(in.gcount()));
    }
    if (in.bad()) throw Error(ErrorKind::Io, "cannot read '" + path.string() + "'", {path.string()});
    return digest.hex();
}

} // namespace strata
