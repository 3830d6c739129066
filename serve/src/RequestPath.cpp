// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/serve/RequestPath.h>

#include <system_error>

namespace strata::serve {

namespace {

namespace fs = std::filesystem;

// `path` (canonical) is `root` (canonical) or lies under it, compared
// component by component (so /srv/bake2 is not inside /srv/bake).
bool isInside(const fs::path& root, const fs::path& path)
{
    auto r = root.begin();
    auto p = path.begin();
    for (; r != root.end(); ++r, ++p) {
        if (p == path.end() || *r != *p) return false;
    }
    return true;
}

// The canonical form of `candidate` if it exists and lies inside `root`:
// 200 with the file, 403 when a link leads out, 404 when nothing is there.
ResolvedPath canonicalInside(const fs::path& root, const fs::path& candidate)
{
    std::error_code ec;
    fs::path canonical = fs::canonical(candidate, ec); // follows every link, fails on a dangling one or a loop
    if (ec) return {404, {}};
    if (!isInside(root, canonical)) return {403, {}};
    return {200, std::move(canonical)};
}

} // namespace

ResolvedPath resolveRequestPath(const fs::path& canonicalRoot, std::string_view decodedPath)
{
    if (decodedPath.empty() || decodedPath.front() != '/') return {400, {}};
    if (decodedPath.find('\0') != std::string_view::npos) return {400, {}};

    // Build the candidate from the segments: ".." anywhere is refused, not
    // resolved (a client that normalises would never send it); a backslash
    // is refused too (a separator elsewhere, and never in a bake's names).
    fs::path candidate = canonicalRoot;
    std::size_t start = 1;
    while (start <= decodedPath.size()) {
        std::size_t end = decodedPath.find('/', start);
        if (end == std::string_view::npos) end = decodedPath.size();
        const std::string_view segment = decodedPath.substr(start, end - start);
        start = end + 1;
        if (segment.empty() || segment == ".") continue;
        if (segment == ".." || segment.find('\\') != std::string_view::npos) return {403, {}};
        candidate /= fs::path(std::string(segment));
    }

    ResolvedPath resolved = canonicalInside(canonicalRoot, candidate);
    if (resolved.status != 200) return resolved;

    std::error_code ec;
    if (fs::is_directory(resolved.file, ec)) {
        if (decodedPath.back() != '/') return {301, {}};
        resolved = canonicalInside(canonicalRoot, resolved.file / "index.html");
        if (resolved.status != 200) return resolved;
    }
    if (!fs::is_regular_file(resolved.file, ec)) return {404, {}}; // a folder index.html, a FIFO, a device
    return resolved;
}

} // namespace strata::serve
