#pragma once
/// \file
/// Each `strata` subcommand lives in its own file and registers itself here:
/// it adds its options to the CLI11 app and returns the action to run when
/// the subcommand was given. main.cpp only parses and dispatches.

#include <CLI/CLI.hpp>

#include <functional>
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
/// Exit code after Ctrl-C (128 + SIGINT, as shells report it).
inline constexpr int EXIT_INTERRUPTED = 130;

/// The exit code of an error kind: bad input 2, interrupted 130, anything
/// else (I/O, GL, internal) 1.
inline int exitCode(ErrorKind kind)
{
    switch (kind) {
    case ErrorKind::BadInput: return EXIT_BAD_INPUT;
    case ErrorKind::Interrupted: return EXIT_INTERRUPTED;
    default: return 1;
    }
}

Command registerGenerateCommand(CLI::App& app);
Command registerSceneCommand(CLI::App& app);
Command registerNodesCommand(CLI::App& app);     // NodesCommand.cpp
Command registerRenderCommand(CLI::App& app);    // RenderCommand.cpp
Command registerMeshCommand(CLI::App& app);      // MeshCommand.cpp
Command registerInfoCommand(CLI::App& app);      // InfoCommand.cpp
Command registerBenchCommand(CLI::App& app);      // BenchCommand.cpp: `bench`, with `bench mesh` under it
Command registerBenchMeshCommand(CLI::App& bench); // BenchMeshCommand.cpp: `bench mesh`, added to `bench`

} // namespace strata::app
