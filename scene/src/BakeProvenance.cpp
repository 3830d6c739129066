// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "BakeProvenance.h"

#include <strata/AtomicFile.h>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <utility>

namespace fs = std::filesystem;

namespace strata::scene::detail {
namespace {

constexpr std::uintmax_t MAX_PROVENANCE_BYTES = 64 * 1024;

std::string hostName()
{
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0) return "unknown";
    return name;
}

std::string environment(const char* name)
{
    const char* value = std::getenv(name);
    return value ? value : "";
}

/// "123_4" for Slurm array task 4 of job 123, "123" for a plain job, the
/// pod's index for a Kubernetes Indexed Job, "" outside a scheduler.
std::string schedulerJob()
{
    const std::string array = environment("SLURM_ARRAY_JOB_ID"), task = environment("SLURM_ARRAY_TASK_ID");
    if (!array.empty() && !task.empty()) return array + "_" + task;
    if (const std::string job = environment("SLURM_JOB_ID"); !job.empty()) return job;
    if (const std::string index = environment("JOB_COMPLETION_INDEX"); !index.empty()) return "index " + index;
    return "";
}

} // namespace

const char* buildArchitecture()
{
#if defined(__x86_64__)
    return "x86_64";
#elif defined(__aarch64__)
    return "aarch64";
#elif defined(__riscv) && __riscv_xlen == 64
    return "riscv64";
#elif defined(__powerpc64__)
    return "ppc64";
#else
    return "unknown";
#endif
}

void writeTileProvenance(const fs::path& dir, int index, double seconds) noexcept
{
    try {
        const auto now = std::chrono::system_clock::now().time_since_epoch();
        nlohmann::json json = {
            {"tile", index},
            {"host", hostName()},
            {"arch", buildArchitecture()},
            {"job", schedulerJob()},
            {"pid", int(getpid())},
            {"finished_unix_s", std::chrono::duration_cast<std::chrono::seconds>(now).count()},
            {"seconds", seconds},
        };
        fs::create_directories(dir / PROVENANCE_FOLDER);
        writeFileAtomically(dir / PROVENANCE_FOLDER / (std::to_string(index) + ".json"), json.dump(1) + "\n");
    } catch (...) {
        // A log: the tile it describes is finished and verified by its record.
    }
}

std::vector<BakeHostTiles> readProvenance(const fs::path& dir, int count)
{
    std::map<std::pair<std::string, std::string>, std::vector<int>> byHost;
    for (int index = 0; index < count; ++index) {
        const fs::path file = dir / PROVENANCE_FOLDER / (std::to_string(index) + ".json");
        // A worker writes a few hundred bytes; anything far larger is not
        // one of ours and is not read (a log must not cost gigabytes).
        std::error_code error;
        const std::uintmax_t bytes = fs::file_size(file, error);
        if (error || bytes > MAX_PROVENANCE_BYTES) continue;
        std::ifstream in(file);
        if (!in) continue;
        const nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions*/ false);
        if (!json.is_object() || !json.contains("host") || !json["host"].is_string() || !json.contains("arch") ||
            !json["arch"].is_string() || json.value("tile", -1) != index)
            continue;
        byHost[{json["host"].get<std::string>(), json["arch"].get<std::string>()}].push_back(index);
    }
    std::vector<BakeHostTiles> out;
    std::vector<bool> reported(std::size_t(std::max(count, 0)), false);
    for (auto& [key, tiles] : byHost) {
        for (const int tile : tiles) reported[std::size_t(tile)] = true;
        out.push_back({key.first, key.second, std::move(tiles)});
    }
    // Workers' tiles whose provenance could not be written (a full disk:
    // the log is best effort, the tile stands) are named, not dropped. A
    // bake with no provenance at all (one process) reports nothing.
    if (!out.empty()) {
        BakeHostTiles unknown{"unknown", "no provenance file", {}};
        for (int index = 0; index < count; ++index)
            if (!reported[std::size_t(index)]) unknown.tiles.push_back(index);
        if (!unknown.tiles.empty()) out.push_back(std::move(unknown));
    }
    return out;
}

} // namespace strata::scene::detail
