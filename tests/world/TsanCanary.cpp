// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Deliberate data races in Strata-named functions, built only under
// ThreadSanitizer (STRATA_TSAN). scripts/sanitizers.sh runs each with the
// world tests' suppressions and requires a report: it proves that TSan is
// active in that build and that tests/world/tsan.supp hides no Strata
// frame, neither on a plain thread nor inside a TBB parallel_for body (the
// TBB frames the file suppresses are in that body's stack).
//   tsan_canary thread | tbb

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdio>
#include <cstring>
#include <thread>

namespace strata::world::canary {

int shared = 0;

__attribute__((noinline)) void raceOnShared(int value)
{
    shared = value; // unsynchronised: the race TSan must report
}

__attribute__((noinline)) void raceInParallelFor()
{
    tbb::parallel_for(tbb::blocked_range<int>(0, 1 << 16, 1), [](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i != r.end(); ++i) shared += i; // unsynchronised across the body's tasks
    });
}

} // namespace strata::world::canary

int main(int argc, char** argv)
{
    using namespace strata::world::canary;
    if (argc == 2 && std::strcmp(argv[1], "thread") == 0) {
        std::thread a([] { raceOnShared(1); });
        std::thread b([] { raceOnShared(2); });
        a.join();
        b.join();
    } else if (argc == 2 && std::strcmp(argv[1], "tbb") == 0) {
        raceInParallelFor();
    } else {
        std::fprintf(stderr, "usage: tsan_canary thread|tbb\n");
        return 2;
    }
    std::printf("tsan canary: shared = %d\n", shared);
    return 0;
}
