// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/serve/MimeType.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <string>
#include <utility>

namespace strata::serve {

namespace {

constexpr std::string_view OCTET_STREAM = "application/octet-stream";

// Extension (lower case, with the dot) → type. glTF's types are the ones
// registered with IANA (model/gltf-binary, model/gltf+json); JavaScript's
// is text/javascript (RFC 9239), which module scripts accept.
constexpr std::array<std::pair<std::string_view, std::string_view>, 22> TYPES = {{
    {".json", "application/json"},
    {".glb", "model/gltf-binary"},
    {".gltf", "model/gltf+json"},
    {".bin", "application/octet-stream"},
    {".html", "text/html; charset=utf-8"},
    {".htm", "text/html; charset=utf-8"},
    {".js", "text/javascript; charset=utf-8"},
    {".mjs", "text/javascript; charset=utf-8"},
    {".css", "text/css; charset=utf-8"},
    {".txt", "text/plain; charset=utf-8"},
    {".md", "text/markdown; charset=utf-8"},
    {".toml", "application/toml"},
    {".svg", "image/svg+xml"},
    {".png", "image/png"},
    {".jpg", "image/jpeg"},
    {".jpeg", "image/jpeg"},
    {".webp", "image/webp"},
    {".ktx2", "image/ktx2"},
    {".exr", "image/x-exr"},
    {".wasm", "application/wasm"},
    {".map", "application/json"},
    {".ico", "image/vnd.microsoft.icon"},
}};

// The type of an extension in TYPES; empty for any other.
std::string_view knownTypeFor(const std::filesystem::path& file)
{
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    for (const auto& [ext, type] : TYPES) {
        if (ext == extension) return type;
    }
    return {};
}

} // namespace

std::string_view mimeTypeFor(const std::filesystem::path& file)
{
    const std::string_view type = knownTypeFor(file);
    return type.empty() ? OCTET_STREAM : type;
}

Compressibility compressibilityOf(std::string_view mimeType)
{
    const std::string_view base = mimeType.substr(0, mimeType.find(';'));
    if (base.starts_with("text/")) return Compressibility::Text;
    constexpr std::array<std::string_view, 4> TEXT = {"application/json", "model/gltf+json", "image/svg+xml",
                                                      "application/toml"};
    if (std::find(TEXT.begin(), TEXT.end(), base) != TEXT.end()) return Compressibility::Text;
    constexpr std::array<std::string_view, 3> BINARY = {"model/gltf-binary", "application/wasm",
                                                        "application/octet-stream"};
    if (std::find(BINARY.begin(), BINARY.end(), base) != BINARY.end()) return Compressibility::Binary;
    return Compressibility::None;
}

Compressibility compressibilityFor(const std::filesystem::path& file)
{
    const std::string_view type = knownTypeFor(file);
    return type.empty() ? Compressibility::None : compressibilityOf(type);
}

} // namespace strata::serve
