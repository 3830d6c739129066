// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/AtomicFile.h>
#include <strata/detail/IntegerHash.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace strata {

namespace {

namespace fs = std::filesystem;

// The registry of live temporaries, read by the signal handler: a fixed array
// of paths (no allocation in the handler), each slot guarded by a state.
constexpr int MAX_TEMPORARIES = 64;
constexpr std::size_t MAX_PATH_BYTES = 4096;
enum SlotState : int { FREE = 0, FILLING = 1, LIVE = 2 };
std::atomic<int> gSlotState[MAX_TEMPORARIES];
char gSlotPath[MAX_TEMPORARIES][MAX_PATH_BYTES];

std::atomic<std::uint64_t> gCounter{0};
std::atomic<bool> gCleanupInstalled{false};
struct sigaction gPrevious[2];

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

int registerTemporary(const fs::path& path)
{
    const std::string& text = path.native();
    if (text.size() >= MAX_PATH_BYTES) return -1;
    for (int i = 0; i < MAX_TEMPORARIES; ++i) {
        int expected = FREE;
        if (gSlotState[i].compare_exchange_strong(expected, FILLING)) {
            std::memcpy(gSlotPath[i], text.c_str(), text.size() + 1);
            gSlotState[i].store(LIVE);
            return i;
        }
    }
    return -1; // full: the write still works, only the signal cleanup misses it
}

void unregisterTemporary(int slot)
{
    if (slot >= 0) gSlotState[slot].store(FREE);
}

extern "C" void cleanupTemporariesOnSignal(int sig)
{
    const int savedErrno = errno;
    for (int i = 0; i < MAX_TEMPORARIES; ++i) {
        if (gSlotState[i].load() == LIVE) ::unlink(gSlotPath[i]);
    }
    const struct sigaction& previous = gPrevious[sig == SIGINT ? 0 : 1];
    if (previous.sa_flags & SA_SIGINFO) {
        if (previous.sa_sigaction) {
            previous.sa_sigaction(sig, nullptr, nullptr);
            errno = savedErrno;
            return;
        }
    } else if (previous.sa_handler == SIG_IGN) {
        errno = savedErrno;
        return;
    } else if (previous.sa_handler != SIG_DFL) {
        previous.sa_handler(sig);
        errno = savedErrno;
        return;
    }
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = SIG_DFL;
    sigemptyset(&action.sa_mask);
    ::sigaction(sig, &action, nullptr);
    ::raise(sig); // pending until the handler returns, then the default action
}

/// One splitmix64 output.
std::uint64_t mix(std::uint64_t x) { return strata::detail::mix64(x + strata::detail::SPLITMIX64_STEP); }

[[noreturn]] void throwIo(const fs::path& target, const std::string& what, int error)
{
    throw Error(ErrorKind::Io, "cannot write '" + target.string() + "': " + what + ": " + std::strerror(error),
                {.file = target.string()});
}

void fsyncFolder(const fs::path& target)
{
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return; // the rename is done; a folder we cannot open cannot be synced
    const int result = ::fsync(fd);
    const int error = errno;
    ::close(fd);
    if (result != 0 && error != EINVAL && error != ENOTSUP && error != EROFS) {
        throwIo(target, "fsync of folder '" + folder.string() + "' failed", error);
    }
}

} // namespace

fs::path temporarySibling(const fs::path& target)
{
    const std::uint64_t n = gCounter.fetch_add(1);
    const std::uint64_t now = std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
    const std::uint64_t random = mix(now ^ mix(n) ^ (std::uint64_t(::getpid()) << 32));
    char suffix[17];
    static const char* const HEX = "0123456789abcdef";
    for (int i = 0; i < 8; ++i) suffix[i] = HEX[(random >> (4 * i)) & 15];
    suffix[8] = '\0';
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on a chain of +.
    std::string name = ".";
    name += target.stem().string();
    name += ".partial-";
    name += std::to_string(::getpid());
    name += "-";
    name += std::to_string(n);
    name += "-";
    name += suffix;
    name += target.extension().string();
    return target.parent_path() / name;
}

void installTemporaryCleanup()
{
    if (gCleanupInstalled.exchange(true)) return;
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = cleanupTemporariesOnSignal;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, &gPrevious[0]);
    ::sigaction(SIGTERM, &action, &gPrevious[1]);
}

void writeFileAtomically(const fs::path& target, std::string_view bytes)
{
    detail::TemporaryFile temporary(target);
    const int fd = ::open(temporary.path().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) throwIo(target, "cannot open temporary '" + temporary.path().string() + "'", errno);
    const char* data = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t written = ::write(fd, data, left);
        if (written < 0) {
            if (errno == EINTR) continue;
            const int error = errno;
            ::close(fd);
            throwIo(target, "write failed after " + std::to_string(bytes.size() - left) + " of " +
                                std::to_string(bytes.size()) + " bytes",
                    error);
        }
        if (written == 0) {
            ::close(fd);
            throwIo(target, "write made no progress", EIO);
        }
        data += written;
        left -= std::size_t(written);
    }
    if (::fsync(fd) != 0) {
        const int error = errno;
        ::close(fd);
        throwIo(target, "fsync failed", error);
    }
    if (::close(fd) != 0) throwIo(target, "close failed", errno);
    temporary.commit(bytes.empty());
}

namespace detail {

TemporaryFile::TemporaryFile(const fs::path& target)
    : mTarget(target)
{
    for (int attempt = 0;; ++attempt) {
        mPath = temporarySibling(target);
        const int fd = ::open(mPath.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            break;
        }
        if (errno != EEXIST || attempt >= 8) {
            throwIo(target, "cannot create temporary '" + mPath.string() + "'", errno);
        }
    }
    mSlot = registerTemporary(mPath);
}

TemporaryFile::~TemporaryFile()
{
    if (!mCommitted) ::unlink(mPath.c_str());
    unregisterTemporary(mSlot);
}

void TemporaryFile::commit(bool allowEmpty)
{
    const int fd = ::open(mPath.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throwIo(mTarget, "the writer left no file at '" + mPath.string() + "'", errno);
    struct stat info;
    if (::fsync(fd) != 0 || ::fstat(fd, &info) != 0) {
        const int error = errno;
        ::close(fd);
        throwIo(mTarget, "fsync failed", error);
    }
    if (::close(fd) != 0) throwIo(mTarget, "close failed", errno);
    if (!S_ISREG(info.st_mode)) throwIo(mTarget, "the writer left no regular file", EINVAL);
    if (info.st_size == 0 && !allowEmpty) {
        throw Error(ErrorKind::Io, "cannot write '" + mTarget.string() + "': the writer produced an empty file",
                    {.file = mTarget.string()});
    }
    if (::rename(mPath.c_str(), mTarget.c_str()) != 0) throwIo(mTarget, "rename failed", errno);
    mCommitted = true;
    fsyncFolder(mTarget);
}

} // namespace detail

} // namespace strata
