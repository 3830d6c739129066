// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// strata — the terrain generator command line. Each subcommand lives in its
// own *Command.cpp file (see Commands.h); this file parses and dispatches.

#include "Commands.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include <iostream>

int main(int argc, char** argv)
{
    using namespace strata::app;
    CLI::App app{"Strata: procedural terrain and caves, sampled into OpenVDB level sets, meshed,\n"
                 "and rendered with height-blended triplanar texturing."};
    app.set_version_flag("--version", "strata 0.1.0");
    app.require_subcommand(1);

    const std::vector<Command> commands = {
        registerGenerateCommand(app),
        registerSceneCommand(app),
        registerNodesCommand(app),
        registerRenderCommand(app),
        registerBakeCommand(app),
        registerExportTerrainCommand(app),
        registerMeshCommand(app),
        registerInfoCommand(app),
        registerServeCommand(app),
        registerBenchCommand(app),
    };

    // SIGINT and SIGTERM remove the temporaries of writes in progress.
    strata::installTemporaryCleanup();
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e); // --help: CLI11 prints the help
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // Flag errors in the one-line format of every other error.
        std::cerr << "strata: error: " << e.what() << " (see strata --help)" << std::endl;
        return EXIT_BAD_INPUT;
    }

    try {
        for (const Command& command : commands) {
            if (command.subcommand->parsed()) return command.run();
        }
        return EXIT_BAD_INPUT; // unreachable: require_subcommand(1)
    } catch (const strata::Error& e) {
        std::cerr << "strata: error: " << e.what() << std::endl;
        return exitCode(e.kind());
    } catch (const std::bad_alloc&) {
        std::cerr << "strata: error: out of memory (lower the voxel size or the region, or set --max-memory)"
                  << std::endl;
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "strata: internal error: " << e.what() << std::endl;
        return 1;
    }
}
