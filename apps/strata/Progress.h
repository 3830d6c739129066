#pragma once
/// \file
/// Terminal output of the CLI: one line per finished stage with its time,
/// and a live percentage while a long stage runs (only when stdout is a TTY).

#include <chrono>
#include <map>
#include <ostream>
#include <string>

namespace strata::app {

class StageLog
{
public:
    /// `out` receives the lines; live progress is shown only if `interactive`.
    StageLog(std::ostream& out, bool interactive, bool quiet);

    /// Starts timing a stage (ends the previous one, if any).
    void begin(const std::string& stage);

    /// Shows "stage  NN%" in place; cheap to call often (redraws at most
    /// once per percent).
    void progress(double fraction);

    /// Ends the current stage, prints "stage  1.234 s  detail", records the time.
    void end(const std::string& detail = "");

    /// Seconds per finished stage, by name.
    const std::map<std::string, double>& seconds() const { return mSeconds; }

    /// Seconds since construction.
    double elapsed() const;

private:
    using Clock = std::chrono::steady_clock;
    std::ostream& mOut;
    bool mInteractive;
    bool mQuiet;
    std::string mStage;
    Clock::time_point mCreated;
    Clock::time_point mStageStart;
    int mShownPercent = -1;
    std::map<std::string, double> mSeconds;
};

/// True when file descriptor 1 is a terminal.
bool stdoutIsTerminal();

} // namespace strata::app
