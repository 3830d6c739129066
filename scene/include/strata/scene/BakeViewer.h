// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The web viewer a bake carries: DIR/viewer/ beside tileset.json holds the
/// page built from web/ (index.html and the bundled viewer.js: three.js,
/// 3d-tiles-renderer and Strata's shading in GLSL ES, generated from
/// shaders/ at build time), the scene's material as the terrain program's
/// uniform values (strata.json) and its maps (maps/*.png).

#include <strata/scene/Scene.h>

#include <filesystem>
#include <string>

namespace strata::scene {

/// The folder of the built viewer page (it holds index.html and
/// viewer.js): $STRATA_VIEWER_DIR when set, else share/strata/viewer of
/// the running executable's prefix, of the install prefix, else the build
/// tree's web/viewer. Empty when none holds the page (built without npm).
std::filesystem::path findViewerPage();

/// Writes `bakeDir`/viewer/ for `scene` (every file atomically, the same
/// bytes from every run): the page from `page`, strata.json and maps/.
/// Returns false, writing nothing, when `page` is empty. Throws
/// strata::Error naming the file for a write failure or a bad material.
bool writeBakeViewer(const std::filesystem::path& bakeDir, const Scene& scene,
                     const std::filesystem::path& page = findViewerPage());

} // namespace strata::scene
