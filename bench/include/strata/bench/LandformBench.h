// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// `strata bench landforms`: how much a terrain's top surface looks like real
/// land. A scene is loaded (its node tree built, which is when an `erode`
/// node evolves: the "global pass"), its top surface sampled
/// (terrain::sampleTopSurface), measured (terrain::measureLandforms, its
/// texture at several cell sizes, its overhangs) and checked against the
/// project's goals (terrain/LandformGoals.h); or a digital elevation model is
/// read (terrain::readElevationFile) and measured the same way (no overhangs:
/// a DEM has no volume). Each stage is reported to a scene::PipelineObserver.
/// docs/landform-statistics.md says what the numbers mean.

#include <strata/scene/Pipeline.h>
#include <strata/terrain/LandformStatistics.h>
#include <strata/terrain/OverhangFraction.h>
#include <strata/terrain/SurfaceTexture.h>

#include <glm/vec2.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace strata::bench {

/// A one-line note for the user (a clipped surface, a cell size that looks
/// like degrees), without the "note: " prefix.
using LandformNote = std::function<void(const std::string& note)>;

struct LandformSceneOptions
{
    std::string scenePath;            ///< empty: the embedded default scene
    double cell = 4.0;                ///< metres between the top surface's columns
    std::optional<glm::dvec2> cropMin, cropMax; ///< x,z corners (default: the scene's region)
    std::vector<double> textureCells; ///< metres; empty: the grid's cell times 1, 2 and 8
    terrain::OverhangOptions overhangs;
};

struct LandformDemOptions
{
    std::string path;
    std::optional<double> cell;       ///< metres; overrides the file's cell size
    std::vector<double> textureCells; ///< metres; empty: the grid's cell times 1, 2 and 8
};

struct LandformBenchResult
{
    terrain::LandformStatistics statistics;
    std::vector<terrain::SurfaceTexture> texture; ///< one per texture cell size
    std::optional<terrain::OverhangStatistics> overhangs; ///< none for a DEM
};

/// The cell sizes the texture is measured at: `requested`, or the grid's
/// cell times 1, 2 and 8. Throws strata::Error (BadInput, naming
/// --texture-cells) for one that is not a whole multiple of `gridCell`.
std::vector<double> landformTextureCells(const std::vector<double>& requested, double gridCell);

/// The checks of a scene run that need no scene (texture cells, overhang
/// step at most the depth), so bad options are refused before the possibly
/// long global pass. Throws strata::Error (BadInput, naming the flag).
void checkLandformSceneOptions(const LandformSceneOptions& options);

/// Loads the scene and measures its top surface: stages "global pass", "top
/// surface", "overhangs  ", "statistics " and "texture    ". Throws
/// strata::Error (BadInput for a bad scene or region; Interrupted when
/// `stages.progress` returns false).
LandformBenchResult measureSceneLandforms(const LandformSceneOptions& options, scene::PipelineObserver& stages,
                                          const LandformNote& note = {});

/// Reads the DEM and measures it: stages "read", "statistics" and
/// "texture   ". Throws strata::Error (BadInput for a DEM without a cell
/// size or with cells without data; what readElevationFile throws).
LandformBenchResult measureDemLandforms(const LandformDemOptions& options, scene::PipelineObserver& stages,
                                        const LandformNote& note = {});

/// The statistics, texture, overhangs (n/a without) and goals as text,
/// starting with a blank line.
std::string formatLandformBench(const LandformBenchResult& result);

} // namespace strata::bench
