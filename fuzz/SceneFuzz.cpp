// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// libFuzzer target for the scene parser (strata::scene::parseScene on TOML
// text). It may return a scene or throw strata::Error; anything else (a
// crash, a sanitizer report, another exception, a scene without a field) is
// a bug. Relative file names in the text (heightmaps, material maps) are
// taken from the working folder; scripts/fuzz.sh runs it in an empty one.

#include <strata/Error.h>
#include <strata/scene/Scene.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        const strata::scene::Scene scene =
            strata::scene::parseScene(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml");
        if (!scene.field || !scene.buildField) {
            std::fprintf(stderr, "parseScene returned a scene without a density field\n");
            std::abort();
        }
    } catch (const strata::Error&) {
        // a rejected input: fine
    }
    return 0;
}
