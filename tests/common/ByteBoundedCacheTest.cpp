// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The one cache facility (ByteBoundedCache.h, CacheMemory.h): least
// recently used dropped first, its own byte budget, the entries it must
// keep, the process-wide limit every cache charges, and threads inserting
// the same key.

#include <strata/ByteBoundedCache.h>
#include <strata/CacheMemory.h>

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

using strata::ByteBoundedCache;

namespace {

using Cache = ByteBoundedCache<int, std::string>;

std::shared_ptr<const std::string> value(const char* text) { return std::make_shared<const std::string>(text); }

/// Restores the process limit when a test ends.
struct LimitGuard
{
    std::uint64_t before = strata::cacheMemoryLimit();
    ~LimitGuard() { strata::setCacheMemoryLimit(before); }
};

} // namespace

TEST(ByteBoundedCache, DropsTheLeastRecentlyUsedToStayWithinItsBudget)
{
    Cache cache(300, 1);
    cache.insert(1, value("a"), 100);
    cache.insert(2, value("b"), 100);
    cache.insert(3, value("c"), 100);
    ASSERT_NE(cache.find(1), nullptr); // 1 is now more recent than 2
    cache.insert(4, value("d"), 100);
    EXPECT_NE(cache.find(1), nullptr);
    EXPECT_EQ(cache.find(2), nullptr);
    EXPECT_NE(cache.find(3), nullptr);
    EXPECT_NE(cache.find(4), nullptr);
    EXPECT_EQ(cache.stats().bytes, 300u);
    EXPECT_EQ(cache.stats().entries, 3u);
    // One value over the whole budget: kept alone (a query needs it), the rest dropped.
    cache.insert(5, value("e"), 1000);
    EXPECT_EQ(cache.stats().entries, 1u);
    EXPECT_NE(cache.find(5), nullptr);
    cache.clear();
    EXPECT_EQ(cache.stats().bytes, 0u);
}

TEST(ByteBoundedCache, KeepsItsMinimumAndWithNoneRefusesValuesOverTheBudget)
{
    Cache keepFour(100, 4);
    for (int i = 0; i < 6; ++i) keepFour.insert(i, value("x"), 100);
    EXPECT_EQ(keepFour.stats().entries, 4u) << "the blocks one query needs together stay";
    Cache keepNone(100, 0);
    const auto big = value("big");
    EXPECT_EQ(keepNone.insert(1, big, 101), big) << "handed back";
    EXPECT_EQ(keepNone.find(1), nullptr) << "but not kept";
    EXPECT_EQ(keepNone.stats().bytes, 0u);
}

TEST(ByteBoundedCache, EveryCacheKeepsWithinTheProcessLimit)
{
    LimitGuard guard;
    const std::uint64_t base = strata::cacheMemoryUsed();
    Cache a(1 << 20, 1), b(1 << 20, 1);
    for (int i = 0; i < 5; ++i) a.insert(i, value("a"), 1000);
    EXPECT_EQ(strata::cacheMemoryUsed(), base + 5000);
    // Under a limit of 3000 more bytes, b's inserts push the total over:
    // b drops its own oldest (a keeps what it has until it inserts).
    strata::setCacheMemoryLimit(base + 3000);
    for (int i = 0; i < 4; ++i) b.insert(i, value("b"), 1000);
    EXPECT_EQ(b.stats().entries, 1u);
    // a's next insert drops its oldest until the process is within the limit.
    a.insert(99, value("a"), 1000);
    EXPECT_EQ(a.stats().entries, 2u);
    EXPECT_NE(a.find(99), nullptr);
    EXPECT_EQ(strata::cacheMemoryUsed(), base + 3000);
    {
        // Over the limit by the one entry a cache must keep, no more.
        Cache c(1 << 20, 1);
        c.insert(1, value("c"), 500);
        c.insert(2, value("c"), 500);
        EXPECT_EQ(c.stats().entries, 1u);
        EXPECT_EQ(strata::cacheMemoryUsed(), base + 3500);
    }
    EXPECT_EQ(strata::cacheMemoryUsed(), base + 3000) << "a cache gone gives its bytes back";
}

TEST(ByteBoundedCache, ThreadsInsertingOneKeyAllGetTheFirstValue)
{
    Cache cache(1 << 20, 1);
    std::vector<std::shared_ptr<const std::string>> got(8);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t) {
        threads.emplace_back([&, t] {
            for (int k = 0; k < 200; ++k) {
                const auto mine = std::make_shared<const std::string>(std::to_string(t));
                const auto kept = cache.insert(k, mine, 10);
                if (k == 199) got[std::size_t(t)] = kept;
            }
        });
    }
    for (std::thread& t : threads) t.join();
    for (const auto& v : got) EXPECT_EQ(v, got[0]);
    EXPECT_EQ(cache.stats().entries, 200u);
    EXPECT_EQ(cache.stats().bytes, 2000u);
}
