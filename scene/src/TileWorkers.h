// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: works through a list of tile indices on TBB, each tile a pure
// function of its index, while the calling thread reports progress and
// hears the observer's interrupt. Needs no Strata library (the observer is
// a template), so its own test builds in seconds under ThreadSanitizer
// (tests/scene/TileWorkersTest.cpp, scripts/sanitizers.sh).

// TSan annotations only (no Strata library): the World's, header-only.
#include <strata/Error.h>
#include <strata/detail/TsanHandOver.h>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <optional>
#include <utility>
#include <vector>

namespace strata::scene::detail {

/// One tile's failure: its message and the kind of its strata::Error
/// (Internal for any other exception), so that a tile refused for its input
/// is reported as bad input (exit 2), not as a failure of the system.
struct TileFailure
{
    int index = 0;
    std::string message;
    ErrorKind kind = ErrorKind::Internal;
    bool operator==(const TileFailure&) const = default;
};

struct TileWorkResult
{
    std::vector<TileFailure> failures; ///< ascending by index
    std::size_t finished = 0;
    bool interrupted = false;
};

/// Runs `work(index)` for every index of `todo`, `threads` tiles at once
/// (0: as many as TBB's default concurrency, the cores this process may
/// use); an exception from `work` is recorded as that tile's failure, with
/// its strata::Error kind (the others go on). Stops handing out tiles once the observer's
/// progressCount() returns false; tiles in progress finish.
///
/// The tiles run as TBB tasks in one task_arena of `threads` slots, so a
/// tile's own parallel_for calls share those threads (one scheduler owns
/// the cores: `threads` threads in all, not `threads` plus TBB's pool).
/// The calling thread stays outside, free for progress and the interrupt;
/// one helper thread enters the arena in its place and takes the slot an
/// entering thread is given, so the arena needs threads − 1 of TBB's
/// workers: the same as any parallel_for called with max_allowed_parallelism
/// = threads (strata bake --threads sets exactly that). Beyond TBB's
/// default (more tiles at once than cores), the limit is raised to
/// `threads` while the tiles run; a lower limit the caller holds still
/// wins (TBB takes the lowest), and then fewer tiles run at once.
/// Each tile runs isolated (tbb::this_task_arena::isolate): a thread
/// waiting inside a tile's parallel_for never picks up another tile.
/// `Observer` (a PipelineObserver, or a test's) has
/// bool progressCount(std::uint64_t done, std::uint64_t total, const std::string& unit).
/// An exception from it stops handing out tiles as an interrupt does; once
/// the tiles in progress have finished and every thread is joined, it is
/// rethrown (a throwing observer used to end the process: std::terminate
/// on the joinable helper thread).
template <class Observer>
TileWorkResult runTileWorkers(const std::vector<int>& todo, int threads, Observer* observer,
                              const std::function<void(int index)>& work)
{
    TileWorkResult result;
    if (todo.empty()) return result;
    // What the runners share, under `mutex` (but `todo` and `work`, which
    // nobody writes while they run).
    struct Shared
    {
        const std::vector<int>& todo;
        const std::function<void(int index)>& work;
        TileWorkResult& result;
        std::mutex mutex;
        std::condition_variable changed;
        std::size_t next = 0;
        bool drained = false; // every runner has returned
    } shared{todo, work, result, {}, {}, 0, false};
    std::mutex& mutex = shared.mutex;
    const int count = std::max(1, std::min<int>(threads > 0 ? threads : tbb::info::default_concurrency(), int(todo.size())));

    std::unique_ptr<tbb::global_control> raise;
    if (tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) < std::size_t(count))
        raise = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(count));
    tbb::task_arena arena(count, 1);

    // A runner takes the next index until none is left or the observer
    // interrupted; `count` runners, one per slot. It captures one pointer,
    // and tells ThreadSanitizer that what the entry thread did before
    // spawning it happens before (TBB's spawn orders it; libtbb is not
    // instrumented, so TSan cannot see that; see strata/detail/TsanHandOver.h).
    Shared* const state = &shared;
    const auto runner = [state] {
        Shared& s = *strata::detail::tsanUncheckedRead(state); // the capture lives in TBB's task memory
        strata::detail::tsanTakeOver(&s);
        for (;;) {
            int index;
            {
                std::lock_guard<std::mutex> hold(s.mutex);
                if (s.result.interrupted || s.next >= s.todo.size()) return;
                index = s.todo[s.next++];
            }
            std::optional<TileFailure> failure;
            try {
                tbb::this_task_arena::isolate([&] { s.work(index); });
            } catch (const Error& e) {
                failure = TileFailure{index, e.what(), e.kind()};
            } catch (const std::exception& e) {
                failure = TileFailure{index, e.what(), ErrorKind::Internal};
            } catch (...) {
                failure = TileFailure{index, "", ErrorKind::Internal};
            }
            if (failure && failure->message.empty()) failure->message = "unknown error";
            std::lock_guard<std::mutex> hold(s.mutex);
            if (failure) s.result.failures.push_back(std::move(*failure));
            ++s.result.finished;
            s.changed.notify_all();
        }
    };
    std::exception_ptr lost;     // from TBB itself (e.g. out of memory), not from a tile
    std::exception_ptr observed; // from the observer
    std::thread entry([&] {
        try {
            arena.execute([&] {
                tbb::task_group group;
                strata::detail::tsanHandOff(&shared);
                for (int r = 0; r < count; ++r) group.run(runner);
                group.wait();
            });
        } catch (...) {
            lost = std::current_exception();
        }
        std::lock_guard<std::mutex> hold(mutex);
        shared.drained = true;
        shared.changed.notify_all();
    });
    {
        // Reports each new count of finished tiles (the last one too), also
        // one that came before this thread first waited; then waits for the
        // next change.
        std::unique_lock<std::mutex> hold(mutex);
        std::size_t reported = 0;
        for (;;) {
            if (result.finished != reported) {
                reported = result.finished;
                hold.unlock();
                bool go = true;
                if (observer && !observed) {
                    try {
                        go = observer->progressCount(reported, todo.size(), "tiles");
                    } catch (...) {
                        observed = std::current_exception();
                        go = false;
                    }
                }
                hold.lock();
                if (!go) result.interrupted = true;
                continue;
            }
            if (shared.drained || result.finished >= todo.size() || (result.interrupted && result.finished == shared.next))
                break;
            shared.changed.wait(hold);
        }
    }
    entry.join();
    if (lost) std::rethrow_exception(lost);
    if (observed) std::rethrow_exception(observed);
    std::sort(result.failures.begin(), result.failures.end(),
              [](const TileFailure& a, const TileFailure& b) { return a.index < b.index; });
    return result;
}

} // namespace strata::scene::detail
