// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Maps a request's path to a file inside the served folder, and refuses
/// every way out of it: `..` segments (plain or percent-encoded: the path
/// given here is decoded once, by the HTTP layer, so `%2e%2e` arrives as
/// `..` and `%252e%252e` as the harmless name `%2e%2e`), NUL bytes,
/// backslashes, relative paths, and symbolic links whose target lies
/// outside the folder. A link inside the folder that points inside it is
/// followed. The check alone leaves a race (a folder on the path swapped for
/// a link before the file is opened): the file server opens the canonical
/// `file` relative to the root's descriptor, following no link at all.

#include <filesystem>
#include <string>
#include <string_view>

namespace strata::serve {

/// What a request path comes to.
struct ResolvedPath
{
    /// 200: serve `file`; 301: a folder named without its trailing slash
    /// (redirect to the path + '/', so the page's relative links work);
    /// 400: not a path (empty, relative, a NUL byte); 403: a way out of the
    /// folder; 404: nothing there (or a folder without index.html, or not a
    /// regular file).
    int status = 404;
    /// The canonical file to serve (status 200 only): no symbolic links,
    /// inside the root.
    std::filesystem::path file{};
};

/// Resolves `decodedPath` (the request target's path, percent-decoded once,
/// without the query) against `canonicalRoot` (an absolute, canonical folder:
/// std::filesystem::canonical()). A folder gives its index.html. Touches
/// the file system (status and canonical of the candidate); never throws.
ResolvedPath resolveRequestPath(const std::filesystem::path& canonicalRoot, std::string_view decodedPath);

} // namespace strata::serve
