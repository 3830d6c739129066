// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "Gzip.h"

#include <strata/Error.h>

#include <zlib.h>

namespace strata::serve::detail {

std::string gzipCompress(std::string_view data, int level)
{
    z_stream stream{};
    // windowBits 15 + 16: a gzip header and trailer instead of zlib's.
    if (deflateInit2(&stream, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        throw Error(ErrorKind::Internal, "gzip: zlib could not start a deflate stream (out of memory?)");
    }
    std::string out(deflateBound(&stream, uLong(data.size())) + 18, '\0'); // + the gzip header and trailer
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    stream.avail_in = uInt(data.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = uInt(out.size());
    const int rc = deflate(&stream, Z_FINISH);
    const uLong written = stream.total_out;
    deflateEnd(&stream);
    if (rc != Z_STREAM_END) throw Error(ErrorKind::Internal, "gzip: zlib deflate failed (code " + std::to_string(rc) + ")");
    out.resize(written);
    out.shrink_to_fit(); // the bound is about the input's size: a body kept in a cache would hold that much
    return out;
}

} // namespace strata::serve::detail
