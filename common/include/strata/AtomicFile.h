#pragma once
/// \file
/// Writing output files so that a failure never leaves a half-written file:
/// write a temporary sibling, then rename it over the target.

#include <strata/Error.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

namespace strata {

/// A hidden sibling of `target` in the same directory (so the final rename is
/// atomic) that keeps the extension, since image and mesh writers pick the
/// format from it: "dir/terrain.glb" → "dir/.terrain.partial-<pid>.glb".
inline std::filesystem::path temporarySibling(const std::filesystem::path& target)
{
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on a chain of +.
    std::string name = ".";
    name += target.stem().string();
    name += ".partial-";
    name += std::to_string(::getpid());
    name += target.extension().string();
    return target.parent_path() / name;
}

/// Calls `write(temporaryPath)`, then renames the temporary file to `target`.
/// If `write` throws, or the rename fails, the temporary file is removed and
/// the exception propagates (a rename failure throws strata::Error).
template <typename WriteFn>
void writeAtomically(const std::filesystem::path& target, WriteFn&& write)
{
    const std::filesystem::path temporary = temporarySibling(target);
    try {
        write(temporary);
        std::error_code ec;
        std::filesystem::rename(temporary, target, ec);
        if (ec) {
            throw Error("cannot write '" + target.string() + "': " + ec.message());
        }
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

} // namespace strata
