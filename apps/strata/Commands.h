// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Each `strata` subcommand lives in its own file and registers itself here:
/// it adds its options to the CLI11 app and returns the action to run when
/// the subcommand was given. main.cpp only parses and dispatches.

#include <CLI/CLI.hpp>

#include <charconv>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include <strata/Error.h>
#include <strata/scene/Scene.h>

namespace strata::app {

// The commands are thin fronts of the scene library: its names are ours.
using namespace strata::scene;

/// The action of one subcommand; returns the process exit code. Throws
/// strata::Error (main maps its kind to the exit code: BadInput 2,
/// Interrupted 130, every other kind 1).
using CommandAction = std::function<int()>;

struct Command
{
    CLI::App* subcommand = nullptr;
    CommandAction run;
};

/// Exit code for bad input: a scene, flag or file the user can fix.
inline constexpr int EXIT_BAD_INPUT = 2;
/// Exit code after Ctrl-C (128 + SIGINT, as shells report it); after
/// SIGTERM it is 143 (128 + SIGTERM).
inline constexpr int EXIT_INTERRUPTED = 130;

/// The signal that interrupted the run (Progress.h), 0 for none.
int interruptSignal();

/// The exit code of an error kind: bad input 2, interrupted 128 + the
/// signal (130 for Ctrl-C, 143 for SIGTERM), anything else (I/O, GL,
/// internal) 1.
inline int exitCode(ErrorKind kind)
{
    switch (kind) {
    case ErrorKind::BadInput: return EXIT_BAD_INPUT;
    case ErrorKind::Interrupted: return interruptSignal() > 0 ? 128 + interruptSignal() : EXIT_INTERRUPTED;
    default: return 1;
    }
}

/// The --seed check: a decimal integer in [0, 2^63 − 1], the range a scene
/// file's `seed` takes, so every seed in a report can go back into a scene
/// (CLI11 alone would clamp 2^64 to 2^64 − 1 and wrap −1).
inline CLI::Validator seedValidator()
{
    return CLI::Validator(
        [](std::string& text) -> std::string {
            std::uint64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ec != std::errc() || ptr != end ||
                value > std::uint64_t(std::numeric_limits<std::int64_t>::max())) {
                return "'" + text + "' is not a seed: use an integer from 0 to 9223372036854775807";
            }
            return {};
        },
        "SEED");
}

Command registerGenerateCommand(CLI::App& app);
Command registerSceneCommand(CLI::App& app);
Command registerNodesCommand(CLI::App& app);     // NodesCommand.cpp
Command registerRenderCommand(CLI::App& app);    // RenderCommand.cpp
Command registerMeshCommand(CLI::App& app);      // MeshCommand.cpp
Command registerInfoCommand(CLI::App& app);      // InfoCommand.cpp
Command registerBakeCommand(CLI::App& app);      // BakeCommand.cpp
Command registerExportTerrainCommand(CLI::App& app); // ExportTerrainCommand.cpp
Command registerServeCommand(CLI::App& app);      // ServeCommand.cpp
Command registerBenchCommand(CLI::App& app);      // BenchCommand.cpp: `bench`, with `bench mesh` under it
Command registerBenchMeshCommand(CLI::App& bench); // BenchMeshCommand.cpp: `bench mesh`, added to `bench`
Command registerBenchNoiseCommand(CLI::App& bench); // BenchNoiseCommand.cpp: `bench noise`, added to `bench`
Command registerBenchLandformsCommand(CLI::App& bench); // BenchLandformsCommand.cpp: `bench landforms`, added to `bench`

} // namespace strata::app
