// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: a pool of threads that works through a list of tile indices,
// each tile a pure function of its index, while the calling thread
// reports progress and hears the observer's interrupt.

#include <strata/scene/Pipeline.h>

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace strata::scene::detail {

struct TileWorkResult
{
    std::vector<std::pair<int, std::string>> failures; ///< (index, message), ascending
    std::size_t finished = 0;
    bool interrupted = false;
};

/// Runs `work(index)` for every index of `todo` on `threads` threads (0:
/// all cores); an exception from `work` is recorded as that tile's failure
/// (the others go on). Stops handing out tiles once the observer's
/// progressCount() returns false; tiles in progress finish.
inline TileWorkResult runTileWorkers(const std::vector<int>& todo, int threads, PipelineObserver* observer,
                                     const std::function<void(int index)>& work)
{
    TileWorkResult result;
    std::mutex mutex;
    std::condition_variable changed;
    std::size_t next = 0;
    const int count = std::max(1, std::min<int>(threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency())),
                                                 int(todo.size())));
    std::vector<std::thread> workers;
    for (int w = 0; w < count && !todo.empty(); ++w) {
        workers.emplace_back([&] {
            for (;;) {
                int index;
                {
                    std::lock_guard<std::mutex> hold(mutex);
                    if (result.interrupted || next >= todo.size()) return;
                    index = todo[next++];
                }
                std::string failure;
                try {
                    work(index);
                } catch (const std::exception& e) {
                    failure = e.what();
                    if (failure.empty()) failure = "unknown error";
                }
                std::lock_guard<std::mutex> hold(mutex);
                if (!failure.empty()) result.failures.emplace_back(index, failure);
                ++result.finished;
                changed.notify_all();
            }
        });
    }
    {
        std::unique_lock<std::mutex> hold(mutex);
        while (result.finished < todo.size() && !(result.interrupted && result.finished == next)) {
            changed.wait(hold);
            const std::size_t done = result.finished;
            hold.unlock();
            const bool go = !observer || observer->progressCount(done, todo.size(), "tiles");
            hold.lock();
            if (!go) result.interrupted = true;
        }
    }
    for (std::thread& worker : workers) worker.join();
    std::sort(result.failures.begin(), result.failures.end());
    return result;
}

} // namespace strata::scene::detail
