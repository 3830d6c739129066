// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/OutputLock.h>

#include <strata/Error.h>

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace strata {

OutputLock::OutputLock(const std::filesystem::path& folder)
    : mPath(folder / ".strata.lock")
{
    mFd = ::open(mPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (mFd < 0) {
        throw Error(ErrorKind::Io, "cannot lock output folder '" + folder.string() + "': " + std::strerror(errno),
                    {folder.string()});
    }
    if (::flock(mFd, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        char holder[32] = {};
        const ssize_t n = ::pread(mFd, holder, sizeof(holder) - 1, 0);
        ::close(mFd);
        mFd = -1;
        if (error == EWOULDBLOCK) {
            const std::string pid = n > 0 ? std::string(holder, std::size_t(n)) : std::string("unknown");
            throw Error(ErrorKind::BadInput,
                        "output folder '" + folder.string() + "' is in use by another strata run (process " +
                            pid.substr(0, pid.find('\n')) + "); wait for it or choose another folder",
                        {folder.string()});
        }
        throw Error(ErrorKind::Io, "cannot lock output folder '" + folder.string() + "': " + std::strerror(error),
                    {folder.string()});
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(mFd, 0) != 0 || ::pwrite(mFd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
        // The pid is only for the message of a second run; the lock holds without it.
    }
}

OutputLock::~OutputLock()
{
    if (mFd < 0) return;
    std::error_code ignored;
    std::filesystem::remove(mPath, ignored); // while still locked: nobody else can be mid-write
    ::flock(mFd, LOCK_UN);
    ::close(mFd);
}

} // namespace strata
