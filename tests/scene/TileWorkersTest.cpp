// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The bake's tile pool (scene/src/TileWorkers.h) on TBB: `threads` tiles at
// once, even beyond the cores and under the max_allowed_parallelism that
// strata bake --threads sets; a tile's parallel_for stays in the pool's
// arena; failures are per tile; the interrupt stops handing out tiles.
// A pool that ran fewer tiles at once than asked would hang the first test
// (its tiles wait for each other): ctest's timeout fails it.
// Its own small target (no Strata library), so scripts/sanitizers.sh runs
// it under ThreadSanitizer in CI for the price of one file.

#include "TileWorkers.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

using strata::scene::detail::runTileWorkers;
using strata::scene::detail::TileFailure;
using strata::scene::detail::TileWorkResult;

namespace {

std::atomic<long> gSum{0};

std::vector<int> indices(int n)
{
    std::vector<int> v(std::size_t(n), 0);
    std::iota(v.begin(), v.end(), 0);
    return v;
}

/// Counts progress reports; interrupts after `stopAfter` of them (< 0: never).
class CountingObserver
{
public:
    explicit CountingObserver(int stopAfter) : mStopAfter(stopAfter) {}
    bool progressCount(std::uint64_t done, std::uint64_t total, const std::string& unit)
    {
        EXPECT_EQ(unit, "tiles");
        EXPECT_LE(done, total);
        last = done;
        ++reports;
        return mStopAfter < 0 || reports < mStopAfter;
    }
    std::uint64_t last = 0;
    int reports = 0;

private:
    int mStopAfter;
};

} // namespace

TEST(TileWorkers, RunsThatManyTilesAtOnceAndTheirParallelForsInTheirArena)
{
    for (const int threads : {1, 2, 3}) {
        // As strata bake --threads N: the process limited to N.
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        std::mutex mutex;
        std::condition_variable all;
        int running = 0, most = 0, arrived = 0;
        std::atomic<int> arenaConcurrency{0};
        std::atomic<long> sum{0};
        gSum = 0;
        CountingObserver observer(-1);
        const TileWorkResult result = runTileWorkers(indices(4 * threads), threads, &observer, [&](int index) {
            {
                std::unique_lock<std::mutex> hold(mutex);
                most = std::max(most, ++running);
                // The first `threads` tiles wait until all of them run at once.
                if (++arrived <= threads) {
                    all.notify_all();
                    all.wait(hold, [&] { return arrived >= threads; });
                }
            }
            arenaConcurrency = tbb::this_task_arena::max_concurrency();
            // Captures nothing: under ThreadSanitizer a capture on this
            // stack read by TBB's workers is a fork edge it cannot see
            // (libtbb is not instrumented; see strata/detail/TsanHandOver.h).
            tbb::parallel_for(0, 1000, [](int i) { gSum += i; });
            sum += 1000L * index;
            std::lock_guard<std::mutex> hold(mutex);
            --running;
        });
        EXPECT_EQ(most, threads);
        EXPECT_EQ(arenaConcurrency.load(), threads) << "a tile's parallel_for runs in the pool's arena";
        EXPECT_EQ(result.finished, std::size_t(4 * threads));
        EXPECT_FALSE(result.interrupted);
        EXPECT_TRUE(result.failures.empty());
        EXPECT_EQ(gSum.load(), 4L * threads * 499500L);
        EXPECT_EQ(sum.load(), 1000L * (4L * threads) * (4L * threads - 1) / 2);
        EXPECT_EQ(observer.last, std::uint64_t(4 * threads)) << "the last report says every tile is done";
    }
}

TEST(TileWorkers, AFailureIsThatTilesTheOthersGoOn)
{
    std::atomic<int> done{0};
    const TileWorkResult result = runTileWorkers(indices(12), 2, static_cast<CountingObserver*>(nullptr), [&](int index) {
        if (index == 7) throw std::runtime_error("seven");
        if (index == 3) throw 3; // not a std::exception
        if (index == 9) throw std::runtime_error("");
        if (index == 10) throw strata::Error(strata::ErrorKind::BadInput, "tile 10 is over its memory budget");
        if (index == 11) throw strata::Error(strata::ErrorKind::Io, "disk full");
        ++done;
    });
    EXPECT_EQ(done.load(), 7);
    EXPECT_EQ(result.finished, 12u);
    ASSERT_EQ(result.failures.size(), 5u);
    using strata::ErrorKind;
    // Each keeps its kind: a tile refused for its input is bad input, not I/O.
    EXPECT_EQ(result.failures[0], (TileFailure{3, "unknown error", ErrorKind::Internal}));
    EXPECT_EQ(result.failures[1], (TileFailure{7, "seven", ErrorKind::Internal}));
    EXPECT_EQ(result.failures[2], (TileFailure{9, "unknown error", ErrorKind::Internal}));
    EXPECT_EQ(result.failures[3], (TileFailure{10, "tile 10 is over its memory budget", ErrorKind::BadInput}));
    EXPECT_EQ(result.failures[4], (TileFailure{11, "disk full", ErrorKind::Io}));
}

TEST(TileWorkers, TheInterruptStopsHandingOutTilesAndTilesInProgressFinish)
{
    for (const int threads : {1, 2, 3}) {
        constexpr int TILES = 2000;
        std::mutex mutex;
        std::condition_variable reported;
        std::vector<int> started, finished;
        // Stops at the first report (after the first tile), so the interrupt
        // comes while tiles are in progress and most are still to hand out.
        // The pool sets its interrupt after the observer returns, before it
        // calls it again, so the tiles after the second wait for the second
        // report: then no tile can be handed out in between, however the
        // threads are scheduled. The second tile waits for the first report
        // and, finishing, brings the second one.
        class StopAtOnce
        {
        public:
            StopAtOnce(std::mutex& m, std::condition_variable& c) : mMutex(m), mReported(c) {}
            bool progressCount(std::uint64_t, std::uint64_t, const std::string&)
            {
                std::lock_guard<std::mutex> hold(mMutex);
                ++reports;
                mReported.notify_all();
                return false;
            }
            int reports = 0;

        private:
            std::mutex& mMutex;
            std::condition_variable& mReported;
        } observer(mutex, reported);
        const TileWorkResult result = runTileWorkers(indices(TILES), threads, &observer, [&](int index) {
            {
                std::unique_lock<std::mutex> hold(mutex);
                started.push_back(index);
                const std::size_t order = started.size();
                if (order == 2) reported.wait(hold, [&] { return observer.reports >= 1; });
                if (order > 2) reported.wait(hold, [&] { return observer.reports >= 2; });
            }
            tbb::parallel_for(0, 20000, [](int) {});
            std::lock_guard<std::mutex> hold(mutex);
            finished.push_back(index);
        });
        EXPECT_TRUE(result.interrupted);
        EXPECT_EQ(started.size(), finished.size()) << "every tile handed out finished";
        EXPECT_EQ(result.finished, finished.size());
        EXPECT_LT(finished.size(), std::size_t(TILES)) << "tiles stopped being handed out";
        EXPECT_TRUE(result.failures.empty());
    }
}

TEST(TileWorkers, AnObserverThatThrowsStopsThePoolAndTheErrorReachesTheCaller)
{
    // PipelineObserver is public API: an observer that throws must not end
    // the process (it did: std::terminate on the joinable helper thread).
    // It stops the tiles as an interrupt does; the tiles in progress finish
    // before the error reaches the caller.
    class Throwing
    {
    public:
        bool progressCount(std::uint64_t, std::uint64_t, const std::string&)
        {
            ++reports;
            throw std::runtime_error("the observer failed");
        }
        int reports = 0;
    };
    for (const int threads : {1, 2, 3}) {
        Throwing observer;
        std::mutex mutex;
        int started = 0, finished = 0;
        try {
            runTileWorkers(indices(500), threads, &observer, [&](int) {
                {
                    std::lock_guard<std::mutex> hold(mutex);
                    ++started;
                }
                tbb::parallel_for(0, 20000, [](int) {});
                std::lock_guard<std::mutex> hold(mutex);
                ++finished;
            });
            ADD_FAILURE() << "no exception with " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "the observer failed");
        }
        EXPECT_EQ(observer.reports, 1) << "asked once, then no more";
        EXPECT_EQ(started, finished) << "every tile handed out finished before the error came back";
    }
}

TEST(TileWorkers, NothingToDo)
{
    CountingObserver observer(-1);
    const TileWorkResult result = runTileWorkers({}, 2, &observer, [](int) { FAIL() << "no tile"; });
    EXPECT_EQ(result.finished, 0u);
    EXPECT_EQ(observer.reports, 0);
}
