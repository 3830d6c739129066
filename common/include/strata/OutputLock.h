// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// One run at a time per output folder: a run's outputs are a set, and two
/// runs writing into the same folder at once would leave a mix of both.

#include <filesystem>

namespace strata {

/// Holds an advisory lock (flock) on FOLDER/.strata.lock while it lives; the
/// file records the holder's process id. The lock dies with the process, so
/// a killed run never leaves the folder locked. The lock file is removed
/// when the lock is released; a process that wins the flock on a file that
/// was removed meanwhile notices (the name points to another inode) and
/// retries, so two processes never both hold the folder (OutputLock.cpp).
class OutputLock
{
public:
    /// Locks `folder` (which must exist). Throws strata::Error (BadInput)
    /// "output folder 'DIR' is in use by another strata run (process PID)"
    /// when another process holds it, or (Io) when the lock file cannot be
    /// created.
    explicit OutputLock(const std::filesystem::path& folder);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

private:
    std::filesystem::path mPath;
    int mFd = -1;
};

} // namespace strata
