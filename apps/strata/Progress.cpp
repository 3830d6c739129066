#include "Progress.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <iomanip>
#include <iostream>
#include <unistd.h>

namespace strata::app {

namespace {

std::atomic<bool> gInterrupted{false};
/// The handler before ours: the temporary-file cleanup (installTemporaryCleanup).
void (*gPrevious)(int) = SIG_DFL;

extern "C" void onInterrupt(int signal)
{
    // The first Ctrl-C asks the pipeline to stop at its next check; a second
    // one goes to the previous handler, which removes temporaries and ends
    // the process at once.
    if (gInterrupted.exchange(true)) {
        std::signal(SIGINT, gPrevious == SIG_ERR ? SIG_DFL : gPrevious);
        std::raise(signal);
    }
}

} // namespace

TerminalProgress::TerminalProgress(std::ostream& out, bool interactive, bool quiet)
    : mOut(out), mInteractive(interactive && !quiet), mQuiet(quiet)
{
    gInterrupted = false;
    gPrevious = std::signal(SIGINT, onInterrupt);
}

TerminalProgress::~TerminalProgress() { std::signal(SIGINT, gPrevious == SIG_ERR ? SIG_DFL : gPrevious); }

void TerminalProgress::beginStage(const std::string& stage)
{
    mStage = stage;
    mShownPercent = -1;
}

bool TerminalProgress::progress(double fraction)
{
    if (gInterrupted) return false;
    if (!mInteractive || mStage.empty()) return true;
    const int percent = int(std::clamp(fraction, 0.0, 1.0) * 100.0);
    if (percent == mShownPercent) return true;
    mShownPercent = percent;
    mOut << "\r  " << std::left << std::setw(10) << mStage << std::right << std::setw(3) << percent << "%"
         << std::flush;
    return true;
}

void TerminalProgress::endStage(const std::string& stage, double seconds, const std::string& detail)
{
    if (!mQuiet) {
        if (mInteractive) mOut << "\r\033[K"; // clear the progress line
        mOut << "  " << std::left << std::setw(10) << stage << std::right << std::fixed << std::setprecision(3)
             << std::setw(8) << seconds << " s";
        if (!detail.empty()) mOut << "   " << detail;
        mOut << std::defaultfloat << std::endl;
    }
    mStage.clear();
}

void TerminalProgress::notice(const std::string& line) { std::cerr << line << std::endl; }

bool stdoutIsTerminal() { return ::isatty(STDOUT_FILENO) == 1; }

bool interruptRequested() { return gInterrupted; }

} // namespace strata::app
