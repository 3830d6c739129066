#include "Progress.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <unistd.h>

namespace strata::app {

StageLog::StageLog(std::ostream& out, bool interactive, bool quiet)
    : mOut(out), mInteractive(interactive && !quiet), mQuiet(quiet), mCreated(Clock::now())
{
}

void StageLog::begin(const std::string& stage)
{
    if (!mStage.empty()) end();
    mStage = stage;
    mShownPercent = -1;
    mStageStart = Clock::now();
}

void StageLog::progress(double fraction)
{
    if (!mInteractive || mStage.empty()) return;
    const int percent = int(std::clamp(fraction, 0.0, 1.0) * 100.0);
    if (percent == mShownPercent) return;
    mShownPercent = percent;
    mOut << "\r  " << std::left << std::setw(10) << mStage << std::right << std::setw(3) << percent << "%"
         << std::flush;
}

void StageLog::end(const std::string& detail)
{
    if (mStage.empty()) return;
    const double seconds = std::chrono::duration<double>(Clock::now() - mStageStart).count();
    mSeconds[mStage] = seconds;
    if (!mQuiet) {
        if (mInteractive) mOut << "\r\033[K"; // clear the progress line
        mOut << "  " << std::left << std::setw(10) << mStage << std::right << std::fixed << std::setprecision(3)
             << std::setw(8) << seconds << " s";
        if (!detail.empty()) mOut << "   " << detail;
        mOut << std::defaultfloat << std::endl;
    }
    mStage.clear();
}

double StageLog::elapsed() const { return std::chrono::duration<double>(Clock::now() - mCreated).count(); }

bool stdoutIsTerminal() { return ::isatty(STDOUT_FILENO) == 1; }

} // namespace strata::app
