// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// FastNoiseLite compiled at run time from the user's copy (see the header).
// A compiler is spawned directly (no shell: any path works), its output goes
// to a file in the temporary folder, and the folder is removed afterwards.

#include "FastNoiseLiteReference.h"

#include <strata/Error.h>

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

namespace strata::terrain::detail {

namespace fs = std::filesystem;

namespace {

// The shim: one C entry point over FastNoiseLite's public API, with the
// settings that match Strata's bases (frequency 1: points are in noise units).
constexpr const char* SHIM = R"(#include "FastNoiseLite.h"
#include <cstddef>
extern "C" void strata_fnl_fill(int basis, int octaves, int dimensions, const float* x, const float* y,
                                const float* z, std::size_t n, float* out)
{
    FastNoiseLite noise(7);
    noise.SetFrequency(1.0f);
    switch (basis) {
    case 0: noise.SetNoiseType(FastNoiseLite::NoiseType_Perlin); break;
    case 1: noise.SetNoiseType(FastNoiseLite::NoiseType_OpenSimplex2); break;
    case 2: noise.SetNoiseType(FastNoiseLite::NoiseType_Value); break;
    default:
        noise.SetNoiseType(FastNoiseLite::NoiseType_Cellular);
        noise.SetCellularDistanceFunction(FastNoiseLite::CellularDistanceFunction_Euclidean);
        noise.SetCellularReturnType(basis == 3 ? FastNoiseLite::CellularReturnType_Distance
                                               : FastNoiseLite::CellularReturnType_Distance2);
    }
    if (octaves > 1) {
        noise.SetFractalType(FastNoiseLite::FractalType_FBm);
        noise.SetFractalOctaves(octaves);
        noise.SetFractalLacunarity(2.0f);
        noise.SetFractalGain(0.5f);
    }
    if (dimensions == 3) {
        for (std::size_t i = 0; i < n; ++i) out[i] = noise.GetNoise(x[i], y[i], z[i]);
    } else {
        for (std::size_t i = 0; i < n; ++i) out[i] = noise.GetNoise(x[i], z[i]);
    }
}
)";

using FillFunction = void (*)(int, int, int, const float*, const float*, const float*, std::size_t, float*);

std::string compilerPath()
{
    if (const char* cxx = std::getenv("CXX"); cxx && *cxx) return cxx;
#ifdef STRATA_CXX_COMPILER
    if (fs::exists(STRATA_CXX_COMPILER)) return STRATA_CXX_COMPILER;
#endif
    return "c++";
}

/// The first `count` lines of a file (the compiler's complaint).
std::string firstLines(const fs::path& file, int count)
{
    std::ifstream in(file);
    std::string line, text;
    for (int i = 0; i < count && std::getline(in, line); ++i) text += "\n  " + line;
    return text;
}

/// Runs argv with stdout and stderr into `log`; returns the exit status, or
/// throws Error(Io) when it cannot start.
int run(const std::vector<std::string>& argv, const fs::path& log)
{
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        throw Error(ErrorKind::Io, "--fastnoise-lite: cannot run the C++ compiler '" + argv[0] + "' (" +
                                       std::strerror(spawned) + "); set CXX to one");
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw Error(ErrorKind::Io, std::string("--fastnoise-lite: waitpid: ") + std::strerror(errno));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

} // namespace

struct FastNoiseLiteReference::Library
{
    fs::path folder;
    void* handle = nullptr;
    FillFunction fill = nullptr;

    ~Library()
    {
        if (handle) dlclose(handle);
        std::error_code ignored;
        if (!folder.empty()) fs::remove_all(folder, ignored);
    }
};

FastNoiseLiteReference::FastNoiseLiteReference(const std::string& header) : mLibrary(std::make_unique<Library>())
{
    std::error_code error;
    if (!fs::is_regular_file(header, error)) {
        throw Error(ErrorKind::BadInput, "--fastnoise-lite: " + header + ": no such file (give the path of FastNoiseLite.h, "
                                         "the C++ version from github.com/Auburn/FastNoiseLite, Cpp/FastNoiseLite.h)");
    }
    std::string pattern = (fs::temp_directory_path(error) / "strata-fastnoise-XXXXXX").string();
    if (error || !mkdtemp(pattern.data())) {
        throw Error(ErrorKind::Io, "--fastnoise-lite: cannot make a temporary folder " + pattern + ": " + std::strerror(errno));
    }
    Library& lib = *mLibrary;
    lib.folder = pattern;
    fs::copy_file(header, lib.folder / "FastNoiseLite.h", error);
    std::ofstream(lib.folder / "shim.cpp") << SHIM;
    if (error || !fs::exists(lib.folder / "shim.cpp")) {
        throw Error(ErrorKind::Io, "--fastnoise-lite: cannot write into " + lib.folder.string());
    }
    const fs::path object = lib.folder / "fastnoiselite.so", log = lib.folder / "compile.log";
    const std::vector<std::string> argv = {compilerPath(), "-std=c++17", "-O3", "-march=native", "-fPIC",
                                           "-shared", "-w",  (lib.folder / "shim.cpp").string(), "-o", object.string()};
    for (const std::string& a : argv) mCommand += (mCommand.empty() ? "" : " ") + a;
    if (const int status = run(argv, log); status != 0) {
        throw Error(ErrorKind::BadInput, "--fastnoise-lite: " + header + " does not compile as FastNoiseLite's C++ header (" +
                                             argv[0] + " exited with " + std::to_string(status) + "):" + firstLines(log, 8));
    }
    lib.handle = dlopen(object.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib.handle) throw Error(ErrorKind::Io, std::string("--fastnoise-lite: cannot load the compiled library: ") + dlerror());
    lib.fill = reinterpret_cast<FillFunction>(dlsym(lib.handle, "strata_fnl_fill"));
    if (!lib.fill) throw Error(ErrorKind::Internal, "--fastnoise-lite: the compiled library has no strata_fnl_fill");
}

FastNoiseLiteReference::~FastNoiseLiteReference() = default;

void FastNoiseLiteReference::fill(ReferenceBasis basis, int octaves, int dimensions, const float* x, const float* y,
                                  const float* z, std::size_t n, float* out) const
{
    mLibrary->fill(int(basis), octaves, dimensions, x, y, z, n, out);
}

} // namespace strata::terrain::detail
