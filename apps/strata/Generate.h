#pragma once
/// \file
/// `strata generate`: scene → grid → mesh → files and snapshot.

#include "Quality.h"
#include "Scene.h"
#include "Snapshot.h"

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/TriangleMesh.h>
#include <strata/render/MeshView.h>
#include <strata/render/SnapshotOptions.h>

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>

namespace strata::app {

struct GenerateOptions
{
    std::filesystem::path outputDir;     ///< created if missing
    std::optional<std::uint64_t> seed;   ///< overrides the scene's seed
    std::optional<int> width, height;    ///< override the snapshot size
    bool snapshot = true;                ///< render snapshot.png (GL backend: needs EGL)
    /// Snapshot renderer (backend auto|gl|cpu), camera (view preset, flags),
    /// turntable and format (png|exr): see Snapshot.h.
    SnapshotRequest request;
    bool writePly = false;               ///< also write terrain.ply
    bool quiet = false;                  ///< no terminal output
    int threads = 0;                     ///< 0 = all cores; recorded in the report
    /// Refuse to sample a grid whose estimated memory exceeds this (bytes;
    /// 0 = no limit): strata::Error with the estimate, before the long stages.
    std::uint64_t maxMemoryBytes = 8ull << 30;
    /// Quality (Quality.h): `--preset` (else the scene's [quality] preset,
    /// else balanced) and `--quality KEY=VALUE` overrides, which win over
    /// the scene. A request.backend other than "auto" counts as a
    /// backend override.
    std::optional<std::string> preset;
    QualityOverrides quality;
};

struct GenerateResult
{
    std::uint64_t seed = 0;
    double voxelSize = 0.0;
    std::uint64_t activeVoxels = 0;
    std::uint64_t evaluatedPoints = 0;  ///< density() + bounds() calls (SampleStats)
    std::uint64_t boundEvaluations = 0; ///< of those, bounds() calls
    std::uint64_t gridMemoryBytes = 0;
    std::uint64_t vertices = 0;
    std::uint64_t triangles = 0;
    std::string renderer;                  ///< GL renderer description, empty without snapshot
    QualitySettings quality;               ///< the effective quality settings
    std::string mesher;                    ///< what meshed it, e.g. "volume (adaptivity 0)"
    /// GL: shader variants compiled for this run against the distinct
    /// feature sets possible (0/0 on the CPU renderer or without snapshot).
    int programsCompiled = 0, programsPossible = 0;
    /// CPU renderer: map fetches done and a naive 3-projection shader's
    /// (render::CpuRenderStats, summed over frames); all 0 on GL.
    std::uint64_t shadedPixels = 0, textureFetches = 0, naiveFetches = 0;
    std::map<std::string, double> timings; ///< seconds per stage, and "total"
};

/// A non-owning render view of `mesh` (valid while `mesh` lives).
render::MeshView meshView(const meshing::TriangleMesh& mesh);

/// The render stage's input: the scene's snapshot size (or `width` ×
/// `height`), camera framing `mesh`, lighting and material (built-in sets
/// generated, texture files loaded). Throws strata::Error for unreadable
/// textures.
render::SnapshotOptions makeSnapshotOptions(const Scene& scene, const meshing::TriangleMesh& mesh,
                                            std::optional<int> width, std::optional<int> height);

/// The same for a snapshot request: its view preset and camera flags on top
/// of the scene's camera (snapshotCamera()); `cave` is the cave view when
/// request.view is "cave".
render::SnapshotOptions makeSnapshotOptions(const Scene& scene, const meshing::TriangleMesh& mesh,
                                            std::optional<int> width, std::optional<int> height,
                                            const SnapshotRequest& request,
                                            const std::optional<render::Camera>& cave = std::nullopt);

/// Meshes `grid` as `quality` says: its mesher (volume with adaptivity, or
/// the chunk meshers in 32³ chunks), normals (grid, face, or `gradient`
/// for "field"), projection steps and simplification (meshoptimizer,
/// borders locked, error bound half a voxel; face normals recomputed).
/// Positions relative to `origin`. `what` receives a short description.
/// Throws strata::Error for "field" normals without a gradient.
meshing::TriangleMesh meshWithQuality(const openvdb::FloatGrid& grid, const QualitySettings& quality,
                                      const meshing::GradientFunction& gradient, const glm::dvec3& origin,
                                      std::string* what = nullptr);

/// Runs the whole pipeline and writes DIR/terrain.vdb, DIR/terrain.glb,
/// (DIR/terrain.ply), DIR/snapshot.png (or .exr; or snapshot_000.png …
/// for a turntable) and DIR/report.json, each atomically.
/// When a snapshot is requested the snapshot request is checked and the EGL
/// context created first (backend gl: an error without one; auto: the CPU
/// renderer, with a notice on stderr), so bad flags write nothing; the cave
/// view is found before any file is written.
/// Throws strata::Error on bad input or an unavailable GL context.
GenerateResult generate(const Scene& scene, const GenerateOptions& options, std::ostream& out);

} // namespace strata::app
