// A deliberate data race in a Strata-named function, built only under
// ThreadSanitizer (STRATA_TSAN). scripts/sanitizers.sh runs it with the world
// tests' suppressions and requires a report: it proves that TSan is active in
// that build and that tests/world/tsan.supp hides no Strata frame.

#include <cstdio>
#include <thread>

namespace strata::world::canary {

int shared = 0;

__attribute__((noinline)) void raceOnShared(int value)
{
    shared = value; // unsynchronised: the race TSan must report
}

} // namespace strata::world::canary

int main()
{
    std::thread a([] { strata::world::canary::raceOnShared(1); });
    std::thread b([] { strata::world::canary::raceOnShared(2); });
    a.join();
    b.join();
    std::printf("tsan canary: shared = %d\n", strata::world::canary::shared);
    return 0;
}
