// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Writing output files so that a failure never leaves a half-written file and
/// never reports success for one: every output goes to a unique temporary
/// sibling, every write and the close are checked, the file is fsync'ed, and
/// only then is it renamed over the target (and the folder fsync'ed). On any
/// error the temporary is removed and the previous file at the target stays
/// untouched.

#include <strata/Error.h>

#include <filesystem>
#include <string_view>

namespace strata {

/// A fresh hidden sibling name for `target` in the same directory (so the final
/// rename is atomic) that keeps the extension, since image and mesh writers
/// pick the format from it: "dir/terrain.glb" →
/// "dir/.terrain.partial-<pid>-<n>-<random>.glb". Unique per call, across
/// threads (a process-wide counter) and processes (pid and a random suffix).
std::filesystem::path temporarySibling(const std::filesystem::path& target);

/// Writes `bytes` to `target` atomically with checked writes (short writes,
/// EINTR, ENOSPC, EFBIG), fsync and a checked close, then renames.
/// Throws strata::Error (ErrorKind::Io) naming `target` on any failure; the
/// temporary is removed and the previous file at `target` is untouched.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

/// Installs SIGINT and SIGTERM handlers that unlink the temporaries of writes
/// in progress (async-signal-safe) and then re-raise the signal with its
/// previous disposition (or call the handler that was installed before).
/// Idempotent. Meant for programs (the CLI's main); libraries never call it.
void installTemporaryCleanup();

namespace detail {

/// A registered, uniquely named temporary file for one atomic write. Created
/// (empty, O_EXCL) by the constructor; removed and unregistered by the
/// destructor unless commit() renamed it.
class TemporaryFile
{
public:
    /// Throws strata::Error (Io) naming `target` if the temporary cannot be created.
    explicit TemporaryFile(const std::filesystem::path& target);
    ~TemporaryFile();
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    const std::filesystem::path& path() const { return mPath; }

    /// Opens the temporary, fsyncs it, checks it is not empty (when
    /// `allowEmpty` is false), renames it to the target and fsyncs the folder.
    /// Throws strata::Error (Io) naming the target on any failure.
    void commit(bool allowEmpty = false);

private:
    std::filesystem::path mTarget;
    std::filesystem::path mPath;
    int mSlot = -1;
    bool mCommitted = false;
};

} // namespace detail

/// Calls `write(temporaryPath)`, which must create the file at that path, then
/// fsyncs it, checks it is not empty and renames it to `target`.
/// If `write` throws, the exception propagates; if the checks or the rename
/// fail, strata::Error (ErrorKind::Io) naming `target` is thrown. Either way
/// the temporary file is removed and the previous file at `target` stays.
/// `write` must check its own stream state: a truncated file cannot be told
/// apart from a short one here.
template <typename WriteFn>
void writeAtomically(const std::filesystem::path& target, WriteFn&& write)
{
    detail::TemporaryFile temporary(target);
    write(temporary.path());
    temporary.commit();
}

} // namespace strata
