// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The file server's cache of gzipped bodies (serve/src/CompressedBodyCache.h):
// keyed by file version, bounded in bytes, least recently used dropped first.

#include "CompressedBodyCache.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

using strata::serve::detail::CompressedBodyCache;
using strata::serve::detail::CompressedBodyKey;

namespace {

CompressedBodyCache::Body bodyOf(std::size_t bytes, char fill = 'z')
{
    auto body = std::make_shared<std::string>(bytes, fill);
    body->shrink_to_fit();
    return body;
}

CompressedBodyKey keyOf(std::uint64_t inode, std::uint64_t modifiedNs = 1)
{
    return {1, inode, 100, modifiedNs, 1};
}

} // namespace

TEST(CompressedBodyCache, AVersionIsFoundUntilItChanges)
{
    CompressedBodyCache cache(1 << 20);
    const auto body = bodyOf(1000);
    EXPECT_EQ(cache.insert(keyOf(7), body), body);
    EXPECT_EQ(cache.find(keyOf(7)), body);
    EXPECT_EQ(cache.find(keyOf(7, 2)), nullptr) << "another modification time is another version";
    EXPECT_EQ(cache.find(keyOf(8)), nullptr) << "another inode is another file";
    CompressedBodyKey otherLevel = keyOf(7);
    otherLevel.level = 9;
    EXPECT_EQ(cache.find(otherLevel), nullptr);
    EXPECT_EQ(cache.bytes(), body->capacity());
    // A second insert of the same version (two requests compressed it at
    // once) keeps the first.
    EXPECT_EQ(cache.insert(keyOf(7), bodyOf(1000, 'y')), body);
    EXPECT_EQ(cache.bytes(), body->capacity());
}

TEST(CompressedBodyCache, TheLeastRecentlyUsedGoFirstAndTheBudgetHolds)
{
    CompressedBodyCache cache(3000);
    cache.insert(keyOf(1), bodyOf(1000));
    cache.insert(keyOf(2), bodyOf(1000));
    ASSERT_NE(cache.find(keyOf(1)), nullptr); // 1 is now more recent than 2
    cache.insert(keyOf(3), bodyOf(1500));     // 2 goes
    EXPECT_NE(cache.find(keyOf(1)), nullptr);
    EXPECT_EQ(cache.find(keyOf(2)), nullptr);
    EXPECT_NE(cache.find(keyOf(3)), nullptr);
    EXPECT_LE(cache.bytes(), 3000u);
    cache.insert(keyOf(4), bodyOf(3000)); // the whole budget: everything else goes
    EXPECT_EQ(cache.find(keyOf(1)), nullptr);
    EXPECT_EQ(cache.find(keyOf(3)), nullptr);
    EXPECT_NE(cache.find(keyOf(4)), nullptr);
    EXPECT_EQ(cache.bytes(), 3000u);
}

TEST(CompressedBodyCache, ABodyLargerThanTheBudgetIsServedNotKept)
{
    CompressedBodyCache cache(1000);
    cache.insert(keyOf(1), bodyOf(500));
    const auto large = bodyOf(1001);
    EXPECT_EQ(cache.insert(keyOf(2), large), large);
    EXPECT_EQ(cache.find(keyOf(2)), nullptr);
    EXPECT_NE(cache.find(keyOf(1)), nullptr) << "a body that cannot be kept drops nothing";
    CompressedBodyCache none(0);
    EXPECT_NE(none.insert(keyOf(1), bodyOf(10)), nullptr) << "still handed back to be sent";
    EXPECT_EQ(none.find(keyOf(1)), nullptr);
    EXPECT_EQ(none.bytes(), 0u);
}

TEST(CompressedBodyCache, ManyThreadsAtOnce)
{
    CompressedBodyCache cache(20000);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t) {
        threads.emplace_back([&cache, t] {
            for (int i = 0; i < 2000; ++i) {
                const auto key = keyOf(std::uint64_t((i * 7 + t) % 50));
                if (!cache.find(key)) cache.insert(key, bodyOf(std::size_t(100 + i % 900)));
                EXPECT_LE(cache.bytes(), 20000u);
            }
        });
    }
    for (std::thread& thread : threads) thread.join();
    EXPECT_LE(cache.bytes(), 20000u);
}
