// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// SHA-256 digests (OpenSSL's libcrypto) as lowercase hex, for manifests
/// that let a later run check files it did not write itself.

#include <filesystem>
#include <string>
#include <string_view>

namespace strata {

/// The SHA-256 of `bytes`, 64 lowercase hex digits.
std::string sha256Hex(std::string_view bytes);

/// The SHA-256 of a file's contents, read in blocks. Throws strata::Error
/// (Io) naming the file when it cannot be read.
std::string sha256File(const std::filesystem::path& path);

} // namespace strata
