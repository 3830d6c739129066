// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The file server's open (serve/src/OpenBeneath.h): a path checked by
// resolveRequestPath() is opened relative to the root's descriptor and never
// through a symbolic link, so a link swapped in after the check cannot lead
// out of the folder. Both ways are checked: openat2 (Linux 5.6 and later) and
// the walk one component at a time used where the kernel lacks it.

#include "OpenBeneath.h"

#include "HttpTestUtil.h"
#include "TestDir.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;
using strata::test::writeFile;

namespace {

using OpenFunction = int (*)(int, const fs::path&);

// root/dir/file.txt holds "inside"; top/out/file.txt and top/secret.txt lie
// beside the root.
class OpenBeneathTest : public testing::TestWithParam<OpenFunction>
{
protected:
    void SetUp() override
    {
        top = strata::test::freshTestDir();
        root = top / "bake";
        writeFile(root / "dir" / "file.txt", "inside");
        writeFile(top / "out" / "file.txt", "TOP SECRET");
        writeFile(top / "secret.txt", "TOP SECRET");
        rootFd = ::open(root.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
        ASSERT_GE(rootFd, 0);
    }
    void TearDown() override
    {
        if (rootFd >= 0) ::close(rootFd);
    }

    // What `relative` opens to: its bytes, or "" when it was refused.
    std::string openAndRead(const fs::path& relative) const
    {
        const int fd = GetParam()(rootFd, relative);
        if (fd < 0) return "";
        std::string bytes(64, '\0');
        const ssize_t n = ::read(fd, bytes.data(), bytes.size());
        ::close(fd);
        bytes.resize(n > 0 ? std::size_t(n) : 0);
        return bytes;
    }

    fs::path top, root;
    int rootFd = -1;
};

} // namespace

TEST_P(OpenBeneathTest, OpensAFileUnderTheRoot)
{
    EXPECT_EQ(openAndRead("dir/file.txt"), "inside");
    EXPECT_EQ(GetParam()(rootFd, "dir/missing.txt"), -1);
    EXPECT_EQ(errno, ENOENT);
}

TEST_P(OpenBeneathTest, AParentFolderSwappedForALinkOutIsNotFollowed)
{
    // resolveRequestPath() saw root/dir as a folder; then, before the open,
    // it became a link to a folder outside.
    fs::rename(root / "dir", root / "dir.old");
    fs::create_directory_symlink("../out", root / "dir");
    ASSERT_EQ(strata::test::readFile(root / "dir" / "file.txt"), "TOP SECRET"); // what following the link gives
    EXPECT_EQ(openAndRead("dir/file.txt"), "");
}

TEST_P(OpenBeneathTest, NoLinkIsFollowedEvenOneThatStaysInside)
{
    // The caller passes the canonical path (links resolved and checked): a
    // link met on the way means the tree changed since.
    fs::create_directory_symlink("dir", root / "link");
    fs::create_symlink("dir/file.txt", root / "file-link.txt");
    EXPECT_EQ(openAndRead("link/file.txt"), "");
    EXPECT_EQ(openAndRead("file-link.txt"), "");
}

TEST_P(OpenBeneathTest, WaysOutAreRefused)
{
    EXPECT_EQ(openAndRead("../secret.txt"), "");
    EXPECT_EQ(openAndRead("dir/../../secret.txt"), "");
    EXPECT_EQ(openAndRead(top / "secret.txt"), "") << "an absolute path";
    EXPECT_EQ(openAndRead("/etc/passwd"), "") << "an absolute path";
}

TEST_P(OpenBeneathTest, AFifoDoesNotBlockTheOpen)
{
    // A FIFO swapped in for a file would block a plain open until a writer
    // comes; the open must return at once (fstat then says it is no file).
    ASSERT_EQ(::mkfifo((root / "dir" / "fifo").c_str(), 0600), 0);
    const int fd = GetParam()(rootFd, "dir/fifo");
    if (fd >= 0) {
        struct stat info{};
        ASSERT_EQ(::fstat(fd, &info), 0);
        EXPECT_FALSE(S_ISREG(info.st_mode));
        ::close(fd);
    }
}

INSTANTIATE_TEST_SUITE_P(Serve, OpenBeneathTest,
                         testing::Values(&strata::serve::detail::openBeneath,
                                         &strata::serve::detail::openBeneathByWalk),
                         [](const testing::TestParamInfo<OpenFunction>& info) {
                             return info.index == 0 ? std::string("Openat2") : std::string("Walk");
                         });
