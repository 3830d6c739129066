// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// One run at a time per output folder (strata/OutputLock.h).

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/OutputLock.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

TEST(OutputLock, ASecondLockOnTheFolderIsRefusedNamingTheHolder)
{
    const std::filesystem::path dir = strata::test::freshTestDir();
    std::optional<strata::OutputLock> first(std::in_place, dir);
    EXPECT_TRUE(std::filesystem::exists(dir / ".strata.lock"));
    try {
        strata::OutputLock second(dir);
        FAIL() << "two locks on one folder";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
        const std::string what = e.what();
        EXPECT_NE(what.find("is in use by another strata run (process " + std::to_string(::getpid()) + ")"),
                  std::string::npos)
            << what;
    }
    first.reset();
    EXPECT_FALSE(std::filesystem::exists(dir / ".strata.lock")) << "the lock file outlives its lock";
    EXPECT_NO_THROW(strata::OutputLock again(dir));
}

TEST(OutputLock, AFolderThatCannotHoldTheLockIsAnIoError)
{
    const std::filesystem::path dir = strata::test::freshTestDir() / "missing";
    try {
        strata::OutputLock lock(dir);
        FAIL() << "locked a folder that does not exist";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Io) << e.what();
        EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
    }
}

namespace {

/// The text of `path`, empty when it cannot be read.
std::string readText(const std::filesystem::path& path)
{
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// One racer: `rounds` times, take the folder's lock (retrying while it is
/// busy), then, as the only writer, write the set a, b, c naming itself and
/// read it back. Exit status: 0 fine, 1 another writer was inside at the
/// same time, 2 the set was mixed, 3 an unexpected error.
int race(const std::filesystem::path& dir, int id, int rounds)
{
    std::minstd_rand random(unsigned(id) * 7919u + 1u);
    const std::string me = std::to_string(id) + "\n";
    for (int round = 0; round < rounds;) {
        try {
            strata::OutputLock lock(dir);
            // The writer marker: O_EXCL fails if another writer is inside.
            const int marker = ::open((dir / "writer").c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
            if (marker < 0) return 1;
            ::close(marker);
            for (const char* name : {"a", "b", "c"}) {
                std::ofstream(dir / name) << me;
                std::this_thread::sleep_for(std::chrono::microseconds(random() % 200));
            }
            for (const char* name : {"a", "b", "c"}) {
                if (readText(dir / name) != me) return 2;
            }
            ::unlink((dir / "writer").c_str());
            ++round;
        } catch (const strata::Error& e) {
            if (e.kind() != strata::ErrorKind::BadInput) {
                std::fprintf(stderr, "racer %d: %s\n", id, e.what());
                return 3;
            }
        }
        std::this_thread::sleep_for(std::chrono::microseconds(random() % 300));
    }
    return 0;
}

} // namespace

// Many processes racing for one folder: never two writers inside at once,
// never a mixed set of files. (The lock file is removed on release; without
// the check that the locked file is still the one its name points to, a
// process that opened the old file could win its flock while another locked
// the new file, and both would write.)
TEST(OutputLock, ManyProcessesRacingForOneFolderNeverWriteAtOnce)
{
    const std::filesystem::path dir = strata::test::freshTestDir();
    constexpr int PROCESSES = 24;
    constexpr int ROUNDS = 40;
    std::vector<pid_t> children;
    std::fflush(nullptr);
    for (int id = 1; id <= PROCESSES; ++id) {
        const pid_t pid = ::fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            ::alarm(120); // a hang fails instead of blocking
            ::_exit(race(dir, id, ROUNDS));
        }
        children.push_back(pid);
    }
    int failures = 0;
    for (const pid_t pid : children) {
        int status = -1;
        ::waitpid(pid, &status, 0);
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            ++failures;
            ADD_FAILURE() << "racer " << pid << ": "
                          << (!WIFEXITED(status)                ? "killed by signal " + std::to_string(WTERMSIG(status))
                              : WEXITSTATUS(status) == 1 ? std::string("two writers at once")
                              : WEXITSTATUS(status) == 2 ? std::string("a mixed set of files")
                                                         : "exit " + std::to_string(WEXITSTATUS(status)));
        }
    }
    EXPECT_EQ(failures, 0);
    const std::string a = readText(dir / "a");
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(readText(dir / "b"), a);
    EXPECT_EQ(readText(dir / "c"), a);
    EXPECT_FALSE(std::filesystem::exists(dir / "writer"));
    EXPECT_FALSE(std::filesystem::exists(dir / ".strata.lock")) << "the lock file outlives its last lock";
}
