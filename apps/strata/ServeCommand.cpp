// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata serve DIR [--port N] [--host ADDR]`: a bake folder over HTTP, for
// the web viewer it holds (viewer/) or any 3D Tiles client. The server is
// strata::serve's FileServer; this file parses the flags, prints the
// address and turns Ctrl-C (SIGINT) and SIGTERM into a clean stop.

#include "Commands.h"

#include <strata/serve/FileServer.h>

#include <atomic>
#include <csignal>
#include <ctime>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

#include <pthread.h>

namespace strata::app {

namespace {

struct ServeFlags
{
    std::string dir;
    int port = 8080;
    std::string host = "127.0.0.1";
    std::string compress = "auto";
    bool log = false;
};

serve::Compression compressionFlag(const ServeFlags& flags)
{
    if (flags.compress == "none") return serve::Compression::None;
    if (flags.compress == "text") return serve::Compression::Text;
    if (flags.compress == "all") return serve::Compression::All;
    return serve::Compression::Auto; // per request, by the client's address
}

int serve(const ServeFlags& flags)
{
    // SIGINT and SIGTERM are blocked in this thread before the server
    // starts its workers (they inherit the mask), and taken by a watcher
    // thread with sigtimedwait(): stop() is not async-signal-safe, so no
    // handler may call it.
    sigset_t stopSignals;
    sigemptyset(&stopSignals);
    sigaddset(&stopSignals, SIGINT);
    sigaddset(&stopSignals, SIGTERM);
    sigset_t previousMask;
    pthread_sigmask(SIG_BLOCK, &stopSignals, &previousMask);
    struct RestoreMask
    {
        sigset_t mask;
        ~RestoreMask() { pthread_sigmask(SIG_SETMASK, &mask, nullptr); }
    } restore{previousMask};

    serve::FileServerOptions options;
    options.host = flags.host;
    options.port = flags.port;
    options.compression = compressionFlag(flags);
    auto logMutex = std::make_shared<std::mutex>();
    if (flags.log) {
        options.onRequest = [logMutex](const serve::RequestRecord& record) {
            std::lock_guard lock(*logMutex);
            std::cout << record.method << " " << record.target << " " << record.status << " " << record.bytes << std::endl;
        };
    }
    serve::FileServer server(flags.dir, options);

    const std::string url = server.url();
    std::cout << "Serving " << flags.dir << " at " << url << "  (Ctrl-C stops)" << std::endl;
    std::error_code ec;
    if (std::filesystem::is_regular_file(server.root() / "viewer" / "index.html", ec)) {
        std::cout << "Viewer: " << url << "viewer/" << std::endl;
    }
    if (!std::filesystem::is_regular_file(server.root() / "tileset.json", ec)) {
        std::cout << "(no tileset.json in " << flags.dir << ": not a bake folder, served as it is)" << std::endl;
    }
    if (!serve::isLoopbackAddress(flags.host)) {
        std::cout << "Note: " << flags.host << " may be reachable from other machines; everything in "
                  << flags.dir << " can be read by them" << std::endl;
    }

    std::atomic<bool> finished{false};
    std::atomic<int> caught{0};
    std::thread watcher([&] {
        while (!finished.load()) {
            const timespec wait{0, 100 * 1000 * 1000};
            const int sig = sigtimedwait(&stopSignals, nullptr, &wait);
            if (sig == SIGINT || sig == SIGTERM) {
                caught = sig;
                server.stop();
                return;
            }
        }
    });
    try {
        server.run();
    } catch (...) {
        finished = true;
        watcher.join();
        throw;
    }
    finished = true;
    watcher.join();
    std::cout << "Stopped" << (caught == SIGINT ? " (Ctrl-C)" : caught == SIGTERM ? " (SIGTERM)" : "") << "." << std::endl;
    return 0;
}

} // namespace

Command registerServeCommand(CLI::App& app)
{
    auto flags = std::make_shared<ServeFlags>();
    CLI::App* command = app.add_subcommand(
        "serve", "Serve a folder (a bake: tileset.json, tiles/, viewer/) read-only over HTTP, on 127.0.0.1 by default");
    command->add_option("dir", flags->dir, "The folder to serve")->required()->check(CLI::ExistingDirectory);
    command->add_option("--port", flags->port, "TCP port; 0 picks a free one (printed)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    command->add_option("--host", flags->host,
                        "Address to listen on; 0.0.0.0 (or ::) serves the folder to every machine that can reach this one")
        ->capture_default_str();
    command
        ->add_option("--compress", flags->compress,
                     "gzip for clients that accept it: text (JSON, JS, HTML, CSS, glTF JSON), all (also .glb, .bin, "
                     ".wasm), none; auto: per request, text for a client on the loopback, all for any other. Never "
                     "ranges, PNG, JPEG or KTX2")
        ->check(CLI::IsMember({"auto", "text", "all", "none"}))
        ->capture_default_str();
    command->add_flag("--log", flags->log, "Print each request: method, target, status, bytes sent");
    return {command, [flags]() { return serve(*flags); }};
}

} // namespace strata::app
