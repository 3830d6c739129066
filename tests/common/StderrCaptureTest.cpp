// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/StderrCapture.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <sys/stat.h>
#include <unistd.h>

namespace {

/// The file descriptor 2 points at (device and inode).
std::pair<dev_t, ino_t> stderrFile()
{
    struct stat st{};
    EXPECT_EQ(::fstat(2, &st), 0);
    return {st.st_dev, st.st_ino};
}

} // namespace

TEST(StderrCapture, TakesWhatLibrariesPrintAndPutsTheStreamBack)
{
    const auto before = stderrFile();
    std::string text;
    {
        strata::StderrCapture capture;
        EXPECT_NE(stderrFile(), before);
        const char raw[] = "libpng error: IDAT: CRC error\n";
        ASSERT_EQ(::write(2, raw, sizeof(raw) - 1), ssize_t(sizeof(raw) - 1));
        std::fprintf(stderr, "libpng warning: second\n");
        text = capture.release();
        EXPECT_EQ(stderrFile(), before);
        EXPECT_EQ(capture.release(), "");
    }
    EXPECT_EQ(text, "libpng error: IDAT: CRC error; libpng warning: second");
    EXPECT_EQ(stderrFile(), before);
}

TEST(StderrCapture, TheDestructorPutsTheStreamBackToo)
{
    const auto before = stderrFile();
    {
        strata::StderrCapture capture;
        std::fprintf(stderr, "dropped\n");
    }
    EXPECT_EQ(stderrFile(), before);
    strata::StderrCapture again; // not deadlocked: the first one let go of the lock
    EXPECT_EQ(again.release(), "");
}
