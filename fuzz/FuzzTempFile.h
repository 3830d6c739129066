// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The fuzz input as a file, for readers that take a path: rewritten for each
// input at one path per process (in /dev/shm when it exists, else TMPDIR or
// /tmp), removed at exit.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace strata::fuzz {

class TempFile
{
public:
    explicit TempFile(const std::string& extension)
    {
        const char* tmp = std::getenv("TMPDIR");
        const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm"
                                          : tmp && *tmp                           ? tmp
                                                                                  : "/tmp";
        mPath = dir / ("strata-fuzz-" + std::to_string(::getpid()) + extension);
    }
    ~TempFile()
    {
        std::error_code ec;
        std::filesystem::remove(mPath, ec);
    }

    /// Writes the bytes; aborts if it cannot (a broken harness, not a finding).
    const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) const
    {
        std::FILE* f = std::fopen(mPath.c_str(), "wb");
        if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
            std::perror("fuzz: cannot write the input file");
            std::abort();
        }
        return mPath;
    }

    const std::filesystem::path& path() const { return mPath; }

private:
    std::filesystem::path mPath;
};

} // namespace strata::fuzz
