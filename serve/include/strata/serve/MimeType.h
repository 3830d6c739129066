// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The Content-Type a file is served with, from its extension, and whether
/// it is worth compressing on the way out.

#include <filesystem>
#include <string_view>

namespace strata::serve {

/// The MIME type of a file from its extension, case-insensitively:
/// `.json` application/json, `.glb` model/gltf-binary, `.gltf`
/// model/gltf+json, `.html` text/html, `.js`/`.mjs` text/javascript, `.css`
/// text/css, `.png` image/png, `.jpg`/`.jpeg` image/jpeg, `.ktx2`
/// image/ktx2, `.wasm` application/wasm, `.bin` application/octet-stream,
/// and a few more (`.txt`, `.md`, `.toml`, `.svg`, `.webp`, `.exr`, `.map`, `.ico`);
/// anything else application/octet-stream. Text types carry
/// `; charset=utf-8`. Never empty.
std::string_view mimeTypeFor(const std::filesystem::path& file);

/// How a type takes to gzip.
enum class Compressibility
{
    None,   ///< compressed already (PNG, JPEG, KTX2, WebP, EXR): sent as it is
    Text,   ///< text, JSON, glTF JSON, SVG: shrinks 5-10x, cheap to compress
    Binary, ///< binary glTF, .bin buffers, WebAssembly: shrinks less (a plain
            ///< tile to 0.72 at zlib level 1), costs about 17 ms a MB
};

/// The compressibility of a type as mimeTypeFor() gives it (parameters
/// such as `; charset=utf-8` are ignored).
Compressibility compressibilityOf(std::string_view mimeType);

/// The compressibility of a file from its extension: that of its type for
/// the extensions mimeTypeFor() knows, None for any other (an unknown
/// extension is application/octet-stream, like `.bin`, but may be a zip,
/// a video or a VDB that gzip only spends time on).
Compressibility compressibilityFor(const std::filesystem::path& file);

} // namespace strata::serve
