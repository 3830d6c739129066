// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Terminal output of the CLI: one line per finished stage with its time, a
/// live percentage while a long stage runs (only when stdout is a TTY), and
/// Ctrl-C: the first SIGINT (or SIGTERM, as Slurm sends) asks the running
/// stage to stop (the pipeline throws an Interrupted error and writes
/// nothing more).

#include <strata/scene/Pipeline.h>

#include <chrono>
#include <ostream>
#include <string>

namespace strata::app {

class TerminalProgress final : public scene::PipelineObserver
{
public:
    /// `out` receives the lines; live progress is shown only if `interactive`.
    TerminalProgress(std::ostream& out, bool interactive, bool quiet);
    ~TerminalProgress() override;

    void beginStage(const std::string& stage) override;
    /// beginStage() unless `stage` is the one running.
    void beginStageOnce(const std::string& stage);
    /// Ends the running stage without a line of its own (its live line is
    /// cleared): for work whose summary is printed elsewhere.
    void dropStage();
    /// Shows "stage  NN%" in place (redraws at most once per percent);
    /// false once SIGINT or SIGTERM arrived.
    bool progress(double fraction) override;
    /// Shows "stage  DONE/TOTAL UNIT  RATE UNIT/min  T left" in place.
    bool progressCount(std::uint64_t done, std::uint64_t total, const std::string& unit) override;
    void endStage(const std::string& stage, double seconds, const std::string& detail) override;
    /// Notices go to stderr, even when quiet.
    void notice(const std::string& line) override;

private:
    std::ostream& mOut;
    bool mInteractive;
    bool mQuiet;
    std::string mStage;
    int mShownPercent = -1;
    std::chrono::steady_clock::time_point mStageStart;
};

/// How the CLI loads a scene: the memory budget (which also becomes the
/// limit of the process's caches, strata/CacheMemory.h), and the erode
/// passes' progress shown as the "erode" stage, stopped by Ctrl-C or
/// SIGTERM (exit 130 or 143) like every other stage.
scene::SceneLoadOptions sceneLoadOptions(std::uint64_t maxMemoryBytes, TerminalProgress& progress);

/// True when file descriptor 1 is a terminal.
bool stdoutIsTerminal();

/// True once SIGINT or SIGTERM arrived while a TerminalProgress was alive.
bool interruptRequested();

/// The signal that asked to stop (SIGINT or SIGTERM), or 0.
int interruptSignal();

} // namespace strata::app
