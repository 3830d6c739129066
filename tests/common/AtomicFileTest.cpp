// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ChildProcess.h"
#include "TestDir.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const fs::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

/// The names in `dir` other than `keep`.
std::vector<std::string> strays(const fs::path& dir, const std::string& keep)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().filename() != keep) names.push_back(entry.path().filename().string());
    }
    return names;
}

} // namespace

TEST(AtomicFile, WritesAndReplacesLeavingNoTemporary)
{
    const auto dir = strata::test::freshTestDir();
    strata::writeFileAtomically(dir / "a.txt", "first");
    EXPECT_EQ(slurp(dir / "a.txt"), "first");
    strata::writeFileAtomically(dir / "a.txt", std::string(100000, 'x'));
    EXPECT_EQ(slurp(dir / "a.txt"), std::string(100000, 'x'));
    EXPECT_TRUE(strays(dir, "a.txt").empty());
}

TEST(AtomicFile, TemporaryNamesAreUniqueAndKeepTheExtension)
{
    std::set<std::string> names;
    for (int i = 0; i < 1000; ++i) {
        const fs::path name = strata::temporarySibling("dir/m.glb");
        EXPECT_EQ(name.extension(), ".glb");
        EXPECT_EQ(name.parent_path(), "dir");
        names.insert(name.string());
    }
    EXPECT_EQ(names.size(), 1000u);
}

TEST(AtomicFile, TwoThreadsSavingToOnePathNeverShareATemporary)
{
    const auto dir = strata::test::freshTestDir();
    const std::string a(50000, 'a'), b(70000, 'b');
    std::vector<std::string> errors[2];
    auto save = [&](int who) {
        for (int i = 0; i < 50; ++i) {
            try {
                strata::writeAtomically(dir / "shared.txt", [&](const fs::path& temporary) {
                    std::ofstream out(temporary, std::ios::binary);
                    out << (who == 0 ? a : b);
                    if (!out.flush()) throw strata::Error(strata::ErrorKind::Io, "flush");
                });
            } catch (const std::exception& e) {
                errors[who].push_back(e.what());
            }
        }
    };
    std::thread first(save, 0), second(save, 1);
    first.join();
    second.join();
    EXPECT_TRUE(errors[0].empty() && errors[1].empty()) << (errors[0].empty() ? errors[1] : errors[0]).front();
    const std::string final = slurp(dir / "shared.txt");
    EXPECT_TRUE(final == a || final == b);
    EXPECT_TRUE(strays(dir, "shared.txt").empty());
}

TEST(AtomicFile, AWriterThatLeavesAnEmptyFileIsAnIoErrorAndTheOldFileStays)
{
    const auto dir = strata::test::freshTestDir();
    spit(dir / "keep.txt", "good");
    try {
        strata::writeAtomically(dir / "keep.txt", [](const fs::path&) {});
        FAIL() << "an empty result was accepted";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Io);
        EXPECT_EQ(e.place().file, (dir / "keep.txt").string());
        EXPECT_NE(std::string(e.what()).find("keep.txt"), std::string::npos) << e.what();
    }
    // A writer that removes its file is also caught.
    EXPECT_THROW(strata::writeAtomically(dir / "keep.txt", [](const fs::path& t) { fs::remove(t); }), strata::Error);
    EXPECT_EQ(slurp(dir / "keep.txt"), "good");
    EXPECT_TRUE(strays(dir, "keep.txt").empty());
}

TEST(AtomicFile, AThrowingWriterLeavesTheOldFileAndNoTemporary)
{
    const auto dir = strata::test::freshTestDir();
    spit(dir / "keep.txt", "good");
    EXPECT_THROW(strata::writeAtomically(dir / "keep.txt",
                                         [](const fs::path& t) {
                                             spit(t, "half");
                                             throw std::runtime_error("boom");
                                         }),
                 std::runtime_error);
    EXPECT_EQ(slurp(dir / "keep.txt"), "good");
    EXPECT_TRUE(strays(dir, "keep.txt").empty());
}

TEST(AtomicFile, MissingFolderIsAnIoErrorNamingTheTarget)
{
    const auto dir = strata::test::freshTestDir();
    try {
        strata::writeFileAtomically(dir / "no" / "such" / "f.txt", "x");
        FAIL();
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Io);
        EXPECT_NE(std::string(e.what()).find("f.txt"), std::string::npos) << e.what();
    }
}

TEST(AtomicFile, FileSizeLimitFailsTheWriteAndKeepsTheOldFile)
{
    const auto dir = strata::test::freshTestDir();
    const std::string good(1000, 'g');
    spit(dir / "big.bin", good);
    const fs::path target = dir / "big.bin";
    const int status = strata::test::runInChild([&] {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{4096, 4096};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return 2;
        try {
            strata::writeFileAtomically(target, std::string(1 << 20, 'n'));
        } catch (const strata::Error& e) {
            const std::string what = e.what();
            return e.kind() == strata::ErrorKind::Io && what.find(target.string()) != std::string::npos ? 0 : 4;
        }
        return 3; // no error: the write lied
    });
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_EQ(slurp(target), good);
    EXPECT_TRUE(strays(dir, "big.bin").empty());
}

TEST(AtomicFile, SignalCleanupRemovesLiveTemporariesAndReRaises)
{
    const auto dir = strata::test::freshTestDir();
    spit(dir / "keep.txt", "good");
    for (int sig : {SIGTERM, SIGINT}) {
        const int status = strata::test::runInChild([&] {
            strata::installTemporaryCleanup();
            strata::installTemporaryCleanup(); // idempotent
            strata::writeAtomically(dir / "keep.txt", [&](const fs::path& temporary) {
                spit(temporary, "partial");
                std::raise(sig);
            });
            return 5; // not reached: the signal kills the child
        });
        ASSERT_TRUE(WIFSIGNALED(status)) << status;
        EXPECT_EQ(WTERMSIG(status), sig);
        EXPECT_EQ(slurp(dir / "keep.txt"), "good");
        EXPECT_TRUE(strays(dir, "keep.txt").empty());
    }
}
