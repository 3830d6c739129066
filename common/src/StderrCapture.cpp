// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/StderrCapture.h>

#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <unistd.h>

namespace strata {

namespace {

std::mutex& captureMutex()
{
    static std::mutex mutex;
    return mutex;
}

/// An unlinked temporary file (O_TMPFILE where the file system has it).
int openTemporary()
{
    const char* dir = std::getenv("TMPDIR");
    const std::string folder = dir && *dir ? dir : "/tmp";
#ifdef O_TMPFILE
    int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd >= 0) return fd;
#endif
    std::string name = folder + "/strata-stderr-XXXXXX";
    fd = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd >= 0) ::unlink(name.c_str());
    return fd;
}

} // namespace

StderrCapture::StderrCapture()
    : mLock(captureMutex())
{
    std::fflush(stderr);
    mCapture = openTemporary();
    if (mCapture < 0) return;
    mSaved = ::fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (mSaved < 0 || ::dup2(mCapture, 2) < 0) {
        if (mSaved >= 0) ::close(mSaved);
        ::close(mCapture);
        mSaved = mCapture = -1;
    }
}

StderrCapture::~StderrCapture()
{
    release();
}

std::string StderrCapture::release()
{
    if (mCapture < 0) return {};
    std::fflush(stderr);
    while (::dup2(mSaved, 2) < 0 && errno == EINTR) {
    }
    ::close(mSaved);
    std::string text;
    char buffer[1000];
    const ssize_t n = ::pread(mCapture, buffer, sizeof(buffer), 0);
    ::close(mCapture);
    mSaved = mCapture = -1;
    if (mLock.owns_lock()) mLock.unlock();
    for (ssize_t i = 0; i < n; ++i) {
        if (buffer[i] == '\n') {
            text += "; ";
        } else if (buffer[i] != '\r') {
            text += buffer[i];
        }
    }
    while (!text.empty() && (text.back() == ' ' || text.back() == ';')) text.pop_back();
    return text;
}

} // namespace strata
