// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Runs a piece of a test in a forked child process, for what must not happen
// in the test process itself: a file size limit, a fatal signal.

#include <csignal>
#include <cstdio>
#include <exception>
#include <functional>

#include <sys/wait.h>
#include <unistd.h>

namespace strata::test {

/// Runs `body` in a forked child and returns its wait status (use
/// WIFEXITED/WEXITSTATUS, WIFSIGNALED/WTERMSIG). The child exits with the
/// value `body` returns, 100 if it throws, and is killed by SIGALRM after
/// `seconds`, so a hang fails the test instead of blocking it. Only
/// single-threaded work belongs in `body` (thread pools do not survive fork).
inline int runInChild(const std::function<int()>& body, unsigned seconds = 60)
{
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::alarm(seconds);
        int rc = 100;
        try {
            rc = body();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "child: unexpected exception: %s\n", e.what());
        } catch (...) {
        }
        std::fflush(nullptr);
        ::_exit(rc);
    }
    int status = -1;
    if (pid > 0) ::waitpid(pid, &status, 0);
    return status;
}

} // namespace strata::test
