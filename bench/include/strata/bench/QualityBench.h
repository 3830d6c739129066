// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// `strata bench`: speed against accuracy, measured. The default scene and
/// the analytic shapes under each quality preset and with each knob swept on
/// its own from `balanced`: sampling + meshing time, triangles, geometric
/// error against the exact shapes (in balanced voxels), render time and PSNR
/// against the `accurate` render. QualityReport.h writes the report.

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/SurfaceError.h>
#include <strata/scene/Quality.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace strata::bench {

/// How big the run is.
struct QualityBenchSize
{
    std::string name;         ///< "tiny", "quick" or "full"
    double halfExtent = 96.0; ///< scene region half size in x and z (metres)
    int width = 640, height = 360; ///< images (pixels)
    int across = 48;          ///< analytic shapes: voxels across 16 m at balanced
    std::vector<meshing::AnalyticShape> shapes;
};

/// The setting: `tiny` (the test setting, seconds), `quick` (under a minute
/// on 2 cores), else the full run.
QualityBenchSize qualityBenchSize(bool tiny, bool quick);

/// One configuration: a preset, or one knob changed from balanced.
struct QualityConfig
{
    std::string name; ///< "fast", "mesher=surface-nets"
    std::string kind; ///< "preset" or "knob"
    std::string preset = "balanced";
    std::string knob, value;
    scene::QualityOverrides overrides;
};

/// Accurate first (the image reference and the camera), then the other
/// presets, then each knob on its own from balanced (`backend=gl` only with
/// `haveGl`).
std::vector<QualityConfig> qualityConfigs(bool haveGl);

/// True for a preset or a knob that changes the mesh (the shapes are
/// measured only for those).
bool changesGeometry(const QualityConfig& config);

/// One measurement: the scene or one shape under one configuration.
struct QualityRow
{
    std::string subject;    ///< "scene", "sphere", ...
    std::size_t config = 0; ///< index into QualityBenchResult::configs
    std::string backend;    ///< "gl", "cpu", or "none" (not rendered)
    scene::QualitySettings quality;
    double voxelSize = 0.0; ///< metres
    std::uint64_t activeVoxels = 0, triangles = 0;
    double meshSeconds = 0.0; ///< sampling + meshing (+ simplification)
    meshing::SurfaceError error; ///< shapes only (the scene has no exact surface)
    double renderSeconds = NAN, psnr = NAN; ///< scene only; psnr against accurate (inf: the reference)
    double psnrBalanced = NAN; ///< against the balanced render (render-only knobs: the same mesh)
    std::uint64_t fetches = 0, naiveFetches = 0; ///< CPU renderer's texture fetches
    int variants = 0; ///< GL program variants compiled so far
};

struct QualityBenchResult
{
    std::string machine;  ///< the CPU model
    int threads = 0;
    QualityBenchSize size;
    double sceneHeight = 0.0;  ///< the default scene region's y extent (metres)
    bool gl = false;           ///< rendered through OpenGL (EGL), else the CPU renderer
    std::string renderer;      ///< the GL renderer's description (with gl)
    int possibleVariants = 0;  ///< the GL renderer's possible program variants (with gl)
    std::vector<QualityConfig> configs;
    std::vector<QualityRow> rows;
    double seconds = 0.0;      ///< the whole run (measuring), wall clock
};

/// Called as the run goes; each may be empty.
struct QualityBenchObserver
{
    /// Before the first measurement: everything but the rows is known.
    std::function<void(const QualityBenchResult&)> started;
    /// After each configuration's scene row.
    std::function<void(const QualityConfig&, const QualityRow&)> sceneMeasured;
};

/// Runs every configuration of qualityConfigs() on the default scene
/// (cropped to `size`) and on `size.shapes`, on `threads` threads (the
/// caller limits TBB; the count is reported). Renders through EGL when it
/// opens, else on the CPU with a notice on `notices`. Throws strata::Error.
QualityBenchResult runQualityBench(const QualityBenchSize& size, int threads, std::ostream& notices,
                                   const QualityBenchObserver& observer = {});

/// The CPU model from /proc/cpuinfo ("unknown CPU" without).
std::string cpuModel();

} // namespace strata::bench
