// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: writing an image file through OpenImageIO so that a failure
// leaves nothing half-written (render::writeImage, render::writeDataImage).

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <functional>
#include <string>

namespace strata::render::detail {

/// OpenImageIO's message on one line: the object's, else the thread's
/// global one, else "unknown OpenImageIO error".
std::string oiioErrorLine(const std::string& objectError);

/// Writes `path` with `encode(output, name)`, which opens `name` on
/// `output` (the writer OpenImageIO picks from the extension), writes and
/// closes it, throwing strata::Error on failure. PNG and EXR are encoded in
/// memory and written with checked writes (OpenImageIO does not always
/// report a failed file write); other formats are written beside `path`
/// under a temporary name that keeps the extension, then checked, synced
/// and renamed. Throws strata::Error (Io) naming `path` when no writer
/// takes the extension.
void writeImageFile(const std::filesystem::path& path,
                    const std::function<void(OIIO::ImageOutput& output, const std::string& name)>& encode);

} // namespace strata::render::detail
