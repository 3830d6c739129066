// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/OutputLock.h>

#include <strata/Error.h>

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace strata {

// The protocol. The lock is an flock on FOLDER/.strata.lock, and the file is
// removed on release, while still locked, so a finished run leaves no lock
// file behind. Removing it opens a race: a process that opened the file
// before the holder removed it can win the flock on that now nameless file
// after the holder lets go, while a third process creates a new file under
// the name and locks that one: both would believe they hold the folder.
// So after winning the flock a process checks that the file it locked is
// still the one the name points to (same device and inode); if not, it lets
// go and starts over with the file now there. Holding the flock on the
// file the name points to is then exclusive: that file has one flock
// holder, and it keeps the name until that holder removes it.
OutputLock::OutputLock(const std::filesystem::path& folder)
    : mPath(folder / ".strata.lock")
{
    for (;;) {
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
        struct stat locked{};
        struct stat named{};
        if (::fstat(mFd, &locked) == 0 && ::stat(mPath.c_str(), &named) == 0 && locked.st_dev == named.st_dev &&
            locked.st_ino == named.st_ino) {
            break;
        }
        // The previous holder removed the file after we opened it: ours is
        // no longer the lock. Let go and open the file the name holds now.
        ::close(mFd);
        mFd = -1;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(mFd, 0) != 0 || ::pwrite(mFd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
        // The pid is only for the message of a second run; the lock holds without it.
    }
}

OutputLock::~OutputLock()
{
    if (mFd < 0) return;
    // Removed while still locked (see the protocol above): a process that
    // opened this file meanwhile finds, once it wins the flock, that the
    // name no longer points to it, and starts over.
    ::unlink(mPath.c_str());
    ::close(mFd); // releases the flock
}

} // namespace strata
