// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// libFuzzer target for one mesh reader, picked at build time by
// STRATA_FUZZ_FORMAT (".ply", ".obj", ".off", ".stl" or ".glb").
// A reader may accept the bytes or throw strata::Error; anything else (a
// crash, a sanitizer report, another exception, a broken mesh) is a bug.

#include <strata/Error.h>
#include <strata/meshing/MeshFile.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace strata::meshing;
    try {
        const TriangleMesh mesh =
            parseMesh(std::string_view(reinterpret_cast<const char*>(data), size), STRATA_FUZZ_FORMAT, "fuzz");
        bool sound = mesh.indices.size() % 3 == 0 && (mesh.normals.empty() || mesh.normals.size() == mesh.positions.size());
        for (std::uint32_t i : mesh.indices) sound = sound && i < mesh.positions.size();
        for (const auto& p : mesh.positions) sound = sound && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        if (!sound) {
            std::fprintf(stderr, "reader returned a broken mesh\n");
            std::abort();
        }
    } catch (const strata::Error&) {
        // a rejected input: fine
    }
    return 0;
}
