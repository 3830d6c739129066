// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The real `strata serve` as a child process: it prints its address, serves
// the bake, and stops cleanly (exit 0) on SIGINT and SIGTERM.

#include <strata/serve/FileServer.h>

#include "HttpTestUtil.h"
#include "TestDir.h"

#include <httplib.h>

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <regex>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

// `strata serve ARGS...` with stdout and stderr on one pipe.
struct Child
{
    pid_t pid = -1;
    int out = -1;
    std::string printed;

    explicit Child(const std::vector<std::string>& args)
    {
        int pipeFds[2];
        if (::pipe(pipeFds) != 0) throw std::runtime_error("pipe failed");
        pid = ::fork();
        if (pid == 0) {
            ::dup2(pipeFds[1], 1);
            ::dup2(pipeFds[1], 2);
            ::close(pipeFds[0]);
            ::close(pipeFds[1]);
            std::vector<char*> argv;
            argv.push_back(const_cast<char*>(STRATA_EXECUTABLE));
            for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
            argv.push_back(nullptr);
            ::execv(STRATA_EXECUTABLE, argv.data());
            ::_exit(127);
        }
        ::close(pipeFds[1]);
        out = pipeFds[0];
    }

    ~Child()
    {
        if (pid > 0 && ::waitpid(pid, nullptr, WNOHANG) == 0) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
        if (out >= 0) ::close(out);
    }

    // Reads what it prints until `pattern` matches or `seconds` pass.
    std::smatch waitFor(const std::regex& pattern, double seconds)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        std::smatch match;
        while (!std::regex_search(printed, match, pattern)) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
            if (left.count() <= 0) break;
            pollfd waiting{out, POLLIN, 0};
            if (::poll(&waiting, 1, int(left.count())) <= 0) break;
            char buffer[4096];
            const ssize_t n = ::read(out, buffer, sizeof(buffer));
            if (n <= 0) break;
            printed.append(buffer, std::size_t(n));
        }
        std::regex_search(printed, match, pattern);
        return match;
    }

    // Reads what is left in the pipe once the child has exited.
    void drain()
    {
        pollfd waiting{out, POLLIN, 0};
        char buffer[4096];
        while (::poll(&waiting, 1, 1000) > 0) {
            const ssize_t n = ::read(out, buffer, sizeof(buffer));
            if (n <= 0) break;
            printed.append(buffer, std::size_t(n));
        }
    }

    // The exit status, or -1 if it has not exited within `seconds`.
    int wait(double seconds)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        int status = 0;
        while (std::chrono::steady_clock::now() < end) {
            if (::waitpid(pid, &status, WNOHANG) == pid) {
                pid = -1;
                drain(); // what it printed last
                return status;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return -1;
    }
};

fs::path makeBake()
{
    const fs::path dir = strata::test::freshTestDir() / "world";
    strata::test::writeFile(dir / "tileset.json", R"({"asset":{"version":"1.1"},"geometricError":1,"root":{}})");
    strata::test::writeFile(dir / "viewer" / "index.html", "<!doctype html>");
    return dir;
}

} // namespace

TEST(ServeCommand, PrintsItsAddressServesTheBakeAndStopsOnCtrlC)
{
    const fs::path dir = makeBake();
    for (const int sig : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGTERM");
        Child child({"serve", dir.string(), "--port", "0", "--log"});
        const std::smatch address =
            child.waitFor(std::regex(R"(Serving \S+ at http://127\.0\.0\.1:(\d+)/  \(Ctrl-C stops\))"), 20);
        ASSERT_FALSE(address.empty()) << "printed: " << child.printed;
        const int port = std::stoi(address[1]);
        EXPECT_GT(port, 0);
        EXPECT_FALSE(child.waitFor(std::regex(R"(http://127\.0\.0\.1:\d+/viewer/)"), 5).empty()) << child.printed;

        httplib::Client client("127.0.0.1", port);
        const auto response = client.Get("/tileset.json");
        ASSERT_TRUE(response);
        EXPECT_EQ(response->status, 200);
        EXPECT_EQ(response->get_header_value("Content-Type"), "application/json");
        EXPECT_EQ(response->body, strata::test::readFile(dir / "tileset.json"));

        const std::string logLine = "GET /tileset.json 200 " + std::to_string(response->body.size());
        EXPECT_FALSE(child.waitFor(std::regex(logLine), 5).empty()) << child.printed;

        ASSERT_EQ(::kill(child.pid, sig), 0);
        const int status = child.wait(15);
        ASSERT_NE(status, -1) << "still running 15 s after the signal; printed: " << child.printed;
        ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        EXPECT_EQ(WEXITSTATUS(status), 0) << child.printed;
        EXPECT_NE(child.printed.find("Stopped"), std::string::npos) << child.printed;
    }
}

TEST(ServeCommand, PortInUseIsAClearErrorWithExitCode1)
{
    const fs::path dir = makeBake();
    strata::serve::FileServerOptions options;
    options.port = 0;
    strata::serve::FileServer holder(dir, options); // bound, not listening: the port is taken
    Child child({"serve", dir.string(), "--port", std::to_string(holder.port())});
    const int status = child.wait(15);
    ASSERT_NE(status, -1);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1) << child.printed;
    EXPECT_NE(child.printed.find("strata: error: serve: cannot listen on 127.0.0.1:" + std::to_string(holder.port())),
              std::string::npos)
        << child.printed;
    EXPECT_NE(child.printed.find("in use"), std::string::npos) << child.printed;
}

TEST(ServeCommand, AMissingFolderIsBadInput)
{
    Child child({"serve", (strata::test::freshTestDir() / "nowhere").string(), "--port", "0"});
    const int status = child.wait(15);
    ASSERT_TRUE(status != -1 && WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << child.printed;
}
