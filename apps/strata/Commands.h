#pragma once
/// \file
/// Each `strata` subcommand lives in its own file and registers itself here:
/// it adds its options to the CLI11 app and returns the action to run when
/// the subcommand was given. main.cpp only parses and dispatches.

#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace strata::app {

/// The action of one subcommand; returns the process exit code. Throws
/// strata::Error for bad input (main turns it into exit code 2).
using CommandAction = std::function<int()>;

struct Command
{
    CLI::App* subcommand = nullptr;
    CommandAction run;
};

/// Exit code for bad input: a scene, flag or file the user can fix.
inline constexpr int EXIT_BAD_INPUT = 2;

Command registerGenerateCommand(CLI::App& app);
Command registerSceneCommand(CLI::App& app);
Command registerRenderCommand(CLI::App& app);    // RenderCommand.cpp
Command registerMeshCommand(CLI::App& app);      // MeshCommand.cpp
Command registerInfoCommand(CLI::App& app);      // InfoCommand.cpp
Command registerBenchCommand(CLI::App& app);      // BenchCommand.cpp: `bench`, with `bench mesh` under it
Command registerBenchMeshCommand(CLI::App& bench); // BenchMeshCommand.cpp: `bench mesh`, added to `bench`

} // namespace strata::app
