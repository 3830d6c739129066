// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// One run at a time per output folder (strata/OutputLock.h).

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/OutputLock.h>

#include <gtest/gtest.h>

#include <optional>
#include <string>
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
