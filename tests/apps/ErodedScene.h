// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// A small terrain with an `erode` node (a 64 m domain at 2 m cells: quick),
// shared by the tests of the landform masks (scene_tests and app_tests).

#include <string>

namespace strata::test {

/// The [terrain.nodes.NAME] table of an `erode` node over the height node `child`.
inline std::string erodeNodeToml(const std::string& name, const std::string& child)
{
    return "[terrain.nodes." + name + "]\ntype = \"erode\"\nheight = \"" + child +
           "\"\nmin = [-32.0, -32.0]\nmax = [32.0, 32.0]\ncell_size = 2.0\n";
}

/// [terrain.nodes.land], a heightfield, and a [region] inside the erode domain.
inline const char* const ERODE_LAND = R"(
[terrain.nodes.land]
type = "heightfield"
amplitude = 10.0
wavelength = 40.0
[region]
min = [-16.0, -10.0, -16.0]
max = [16.0, 10.0, 16.0]
)";

/// A whole scene (seed 3): the root is an `erode` node over `land`; the
/// caller appends its other tables.
inline std::string erodedSceneToml()
{
    return "seed = 3\n[terrain]\nroot = \"eroded\"\n" + erodeNodeToml("eroded", "land") + ERODE_LAND;
}

} // namespace strata::test
