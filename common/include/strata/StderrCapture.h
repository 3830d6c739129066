// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Keeps third-party libraries from printing on the standard error stream.
/// libpng (under OpenImageIO) prints "libpng error: ..." and "libpng
/// warning: ..." lines on file descriptor 2 for a corrupt image before
/// OpenImageIO reports the same failure through its own error API; Strata
/// reports failures as one strata::Error, so those lines are captured here
/// instead of reaching the user's terminal.

#include <mutex>
#include <string>

namespace strata {

/// While it lives, whatever is written to file descriptor 2 (by any thread)
/// goes into a temporary file instead of the real stream; the destructor or
/// release() puts the stream back. Captures are serialised by a process-wide
/// mutex (file descriptor 2 is one per process), so do not nest them.
/// If the temporary file cannot be made, nothing is captured (the library's
/// lines reach stderr as before); never throws.
class StderrCapture
{
public:
    StderrCapture();
    ~StderrCapture();
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;

    /// Puts the stream back and returns what was captured, in one line
    /// (newlines become "; ", trailing blanks dropped; at most 1000 bytes).
    /// Later calls return "".
    std::string release();

private:
    std::unique_lock<std::mutex> mLock;
    int mSaved = -1;   ///< duplicate of the original descriptor 2
    int mCapture = -1; ///< the temporary file
};

} // namespace strata
