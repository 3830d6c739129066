// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "Progress.h"

#include <strata/CacheMemory.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <iomanip>
#include <iostream>
#include <unistd.h>

namespace strata::app {

namespace {

std::atomic<bool> gInterrupted{false};
/// The first stop signal (SIGINT or SIGTERM), 0 before one arrived.
std::atomic<int> gSignal{0};
/// The handlers before ours (SIGINT, SIGTERM): the temporary-file cleanup
/// (installTemporaryCleanup).
void (*gPrevious[2])(int) = {SIG_DFL, SIG_DFL};

int slot(int signal) { return signal == SIGINT ? 0 : 1; }

void restore(int signal)
{
    void (*previous)(int) = gPrevious[slot(signal)];
    std::signal(signal, previous == SIG_ERR ? SIG_DFL : previous);
}

extern "C" void onInterrupt(int signal)
{
    // The first Ctrl-C or SIGTERM (what Slurm sends on scancel and at its
    // time limit) asks the pipeline to stop at its next check; a second one
    // goes to the previous handler, which removes temporaries and ends the
    // process at once.
    int none = 0;
    gSignal.compare_exchange_strong(none, signal);
    if (gInterrupted.exchange(true)) {
        restore(signal);
        std::raise(signal);
    }
}

} // namespace

TerminalProgress::TerminalProgress(std::ostream& out, bool interactive, bool quiet)
    : mOut(out), mInteractive(interactive && !quiet), mQuiet(quiet)
{
    gInterrupted = false;
    gSignal = 0;
    gPrevious[0] = std::signal(SIGINT, onInterrupt);
    gPrevious[1] = std::signal(SIGTERM, onInterrupt);
}

TerminalProgress::~TerminalProgress()
{
    restore(SIGINT);
    restore(SIGTERM);
}

void TerminalProgress::beginStageOnce(const std::string& stage)
{
    if (mStage != stage) beginStage(stage);
}

void TerminalProgress::dropStage()
{
    if (mInteractive && mShownPercent >= 0) mOut << "\r\033[K" << std::flush;
    mStage.clear();
    mShownPercent = -1;
}

void TerminalProgress::beginStage(const std::string& stage)
{
    mStage = stage;
    mShownPercent = -1;
    mStageStart = std::chrono::steady_clock::now();
}

bool TerminalProgress::progressCount(std::uint64_t done, std::uint64_t total, const std::string& unit)
{
    if (gInterrupted) return false;
    if (!mInteractive || mStage.empty()) return true;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - mStageStart).count();
    mOut << "\r\033[K  " << std::left << std::setw(10) << mStage << std::right << done << "/" << total << " " << unit;
    if (done > 0 && seconds > 0.0) {
        const double perMinute = 60.0 * double(done) / seconds;
        const double left = seconds / double(done) * double(total - done);
        mOut << std::fixed << std::setprecision(1) << "  " << perMinute << " " << unit << "/min  ";
        if (left >= 60.0) mOut << int(left / 60.0) << " min " << int(left) % 60 << " s left";
        else mOut << int(left + 0.5) << " s left";
        mOut << std::defaultfloat;
    }
    mOut << std::flush;
    return true;
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

scene::SceneLoadOptions sceneLoadOptions(std::uint64_t maxMemoryBytes, TerminalProgress& progress)
{
    scene::SceneLoadOptions load;
    load.maxMemoryBytes = maxMemoryBytes;
    // The caches (erosion grids, detail blocks, worm buckets) keep within it too.
    setCacheMemoryLimit(maxMemoryBytes);
    // The passes' times are printed with the scene (the "landform" lines).
    load.progress = [&progress](double fraction) {
        progress.beginStageOnce("erode");
        const bool go = progress.progress(fraction);
        if (fraction >= 1.0) progress.dropStage();
        return go;
    };
    return load;
}

bool stdoutIsTerminal() { return ::isatty(STDOUT_FILENO) == 1; }

bool interruptRequested() { return gInterrupted; }

int interruptSignal() { return gSignal; }

} // namespace strata::app
