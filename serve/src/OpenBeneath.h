// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Opens a file by its path relative to the served folder's descriptor,
// without following any symbolic link and without leaving the folder.
// resolveRequestPath() checks a path with canonical(), which follows links;
// opening the path it returned by name would follow a link swapped in for
// one of its folders after the check (the check-then-open race). Opening it
// relative to the root's descriptor, refusing every link, closes that: the
// canonical path has none, so a link met here is a change since the check.
//
// openat2(RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS) does it in the kernel
// (Linux 5.6); where the kernel lacks it (ENOSYS, or EPERM from a container's
// seccomp filter that predates it) the path is walked a component at a time
// with openat(O_NOFOLLOW). Header-only: the file server and its tests.

#include <cerrno>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace strata::serve::detail {

// Read-only; O_NONBLOCK so that a FIFO swapped in for a file does not block
// the open (the server then sees by fstat that it is no regular file).
inline constexpr int OPEN_BENEATH_FLAGS = O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK;

/// `relative` opened under `rootFd` one component at a time: every folder
/// with openat(O_PATH | O_DIRECTORY | O_NOFOLLOW), the file with
/// OPEN_BENEATH_FLAGS. Returns the descriptor, or -1 with errno: EXDEV for
/// an absolute path or a `..` component, ELOOP or ENOTDIR for a link, what
/// openat gives otherwise (ENOENT, EACCES).
inline int openBeneathByWalk(int rootFd, const std::filesystem::path& relative)
{
    if (relative.is_absolute()) {
        errno = EXDEV;
        return -1;
    }
    std::string last;
    int dirFd = -1; // -1: still the root, which is not ours to close
    const auto closeDir = [&dirFd] {
        if (dirFd >= 0) {
            const int saved = errno;
            ::close(dirFd);
            errno = saved;
        }
    };
    for (const std::filesystem::path& part : relative) {
        const std::string name = part.string();
        if (name.empty() || name == ".") continue;
        if (name == "..") {
            closeDir();
            errno = EXDEV;
            return -1;
        }
        if (!last.empty()) {
            // O_PATH | O_NOFOLLOW would open a link itself: O_DIRECTORY makes
            // that ENOTDIR, and the fstat below is a second check.
            const int next = ::openat(dirFd >= 0 ? dirFd : rootFd, last.c_str(),
                                      O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            closeDir();
            if (next < 0) return -1;
            dirFd = next;
            struct stat info{};
            if (::fstat(dirFd, &info) != 0 || !S_ISDIR(info.st_mode)) {
                closeDir();
                errno = ENOTDIR;
                return -1;
            }
        }
        last = name;
    }
    if (last.empty()) {
        errno = EISDIR; // the root itself
        closeDir();
        return -1;
    }
    const int fd = ::openat(dirFd >= 0 ? dirFd : rootFd, last.c_str(), OPEN_BENEATH_FLAGS);
    closeDir();
    return fd;
}

/// `relative` (a path under the root, as resolveRequestPath() leaves it
/// canonical) opened under `rootFd` (an O_PATH or O_RDONLY descriptor of the
/// root folder) with OPEN_BENEATH_FLAGS, following no symbolic link, magic
/// /proc link or `..` out of the root. Returns the descriptor, or -1 with
/// errno (EXDEV: a way out; ELOOP: a link; ENOENT ...).
inline int openBeneath(int rootFd, const std::filesystem::path& relative)
{
#ifdef SYS_openat2
    open_how how{};
    how.flags = OPEN_BENEATH_FLAGS;
    how.resolve = RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS | RESOLVE_NO_MAGICLINKS;
    const long fd = ::syscall(SYS_openat2, rootFd, relative.c_str(), &how, sizeof(how));
    if (fd >= 0 || (errno != ENOSYS && errno != EPERM)) return int(fd);
    // EPERM: an old seccomp filter that refuses the syscall it does not know,
    // or a real permission error, which the walk reports again.
#endif
    return openBeneathByWalk(rootFd, relative);
}

} // namespace strata::serve::detail
