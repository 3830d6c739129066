// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// gzip (RFC 1952) in memory through zlib, for the file server's
// Content-Encoding: gzip of the types cpp-httplib does not compress itself.

#include <string>
#include <string_view>

namespace strata::serve::detail {

/// `data` as one gzip member at zlib `level` (1-9), its capacity trimmed to
/// its size (it may be kept in a cache). Throws strata::Error
/// (Internal) if zlib fails (out of memory).
std::string gzipCompress(std::string_view data, int level);

} // namespace strata::serve::detail
