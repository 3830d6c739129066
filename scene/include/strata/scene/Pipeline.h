// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The generate pipeline as library functions: sample → mesh → write →
/// render → report. Each stage is callable on its own with the grid and mesh
/// in memory; generate() runs them all, as `strata generate` does, and
/// reports progress through a PipelineObserver (the CLI's progress line and
/// Ctrl-C).

#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>
#include <strata/scene/Snapshot.h>

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/TriangleMesh.h>
#include <strata/render/Image.h>
#include <strata/render/MeshView.h>
#include <strata/render/SnapshotOptions.h>
#include <strata/terrain/SampleLevelSet.h>

#include <openvdb/openvdb.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene {

/// Hears about the stages of a long run. Every method has a do-nothing
/// default; calls come from the thread that called the pipeline.
class PipelineObserver
{
public:
    virtual ~PipelineObserver() = default;
    /// A stage starts: "context", "material", "generate", "cave", "mesh", "write", "render".
    virtual void beginStage(const std::string& stage) {}
    /// Fraction of the current stage done, 0..1 (only long stages report).
    /// Return false to stop: the stage throws strata::Error of kind
    /// Interrupted, and nothing more is written.
    virtual bool progress(double fraction) { return true; }
    /// Progress of a stage that counts items (the bake's tiles): `done` of
    /// `total` `unit`s. Same contract as progress(), which it calls by default.
    virtual bool progressCount(std::uint64_t done, std::uint64_t total, const std::string& unit)
    {
        return progress(total ? double(done) / double(total) : 1.0);
    }
    /// The current stage ended after `seconds`; `detail` sums it up in words.
    virtual void endStage(const std::string& stage, double seconds, const std::string& detail) {}
    /// A one-line notice for the user (e.g. the GL fallback to the CPU).
    virtual void notice(const std::string& line) {}
};

/// Stage 1's result: the terrain sampled into a narrow-band level set.
struct SampledTerrain
{
    std::uint64_t seed = 0;
    std::shared_ptr<const terrain::DensityField> field; ///< the root field for `seed`
    /// The tree's landform source for `seed` (Scene::landformMasks), or null.
    std::shared_ptr<const terrain::LandformMasks> landformMasks;
    /// The tree's rock source for `seed` (Scene::rockMasks), or null.
    std::shared_ptr<const terrain::RockMasks> rockMasks;
    openvdb::FloatGrid::Ptr grid; ///< named "terrain"
    terrain::SampleStats stats;
};

/// Stage 1: the scene's terrain for `seed` (default: the scene's own; another
/// seed rebuilds the node tree) sampled into a level set over the scene's
/// region with its voxel size and band. Refuses grids whose estimated memory
/// exceeds `maxMemoryBytes` (0 = no limit) before sampling. `progress` may be
/// empty; returning false from it interrupts (strata::Error, Interrupted).
SampledTerrain sampleTerrain(const Scene& scene, std::optional<std::uint64_t> seed = std::nullopt,
                             std::uint64_t maxMemoryBytes = 0,
                             const std::function<bool(double)>& progress = {});

/// The density field's own gradient by central differences `step` metres
/// apart ("field" normals). Keeps a reference to `field`.
meshing::GradientFunction fieldGradient(std::shared_ptr<const terrain::DensityField> field, double step);

/// Stage 2: the terrain mesh, as the quality settings say, with positions
/// relative to the region's centre (mesh.origin). `what` receives a short
/// description of the mesher. The per-vertex attributes layer rules read
/// come with it: cavity and cover (mesh.surface) when a rule has a cavity
/// or cover band; the landform masks (mesh.landform,
/// computeLandformAttributes()) when a rule has a flow, wear, deposition or
/// water band, or `extra.landform` (a landform debug view; needsLandform());
/// the rock masks (mesh.rock, computeRockAttributes()) when a rule has a
/// hardness or bed band, or `extra.rock`. Throws strata::Error (BadInput)
/// when the terrain has no surface inside the region, or when masks are
/// needed and the terrain has no source for them.
struct MeshMasks
{
    bool landform = false;
    bool rock = false;
};
meshing::TriangleMesh meshTerrain(const Scene& scene, const QualitySettings& quality, const SampledTerrain& terrain,
                                  std::string* what = nullptr, MeshMasks extra = {});

/// Whether a render of `scene` with debug view `debugView` (a
/// render::debugViewName(), or empty) needs the mesh's landform masks: a
/// layer rule reads them, or the view is a landform view (flow, wear,
/// deposition, water). Throws strata::Error (BadInput) when it does and the
/// scene's terrain has no landform source (an `erode` node).
bool needsLandform(const Scene& scene, const std::string& debugView = "");

/// As needsLandform(), for the rock masks: a layer rule has a hardness or
/// bed band, or the view is a rock view (hardness, bed). Throws when the
/// scene's terrain has no rock source (a `beds` node).
bool needsRock(const Scene& scene, const std::string& debugView = "");

/// {needsLandform(), needsRock()} for a render with `debugView`.
MeshMasks neededMasks(const Scene& scene, const std::string& debugView = "");

/// Stage 3: writes DIR/terrain.vdb, DIR/terrain.glb (and DIR/terrain.ply),
/// each atomically. Throws strata::Error (I/O) naming the file on failure.
void writeTerrain(const SampledTerrain& terrain, const meshing::TriangleMesh& mesh,
                  const std::filesystem::path& outputDir, bool writePly = false);

/// Counts of the render stage (for the report).
struct RenderStats
{
    /// GL: shader variants compiled against the distinct feature sets possible.
    int programsCompiled = 0, programsPossible = 0;
    /// CPU renderer: map fetches done and a naive 3-projection shader's.
    std::uint64_t shadedPixels = 0, textureFetches = 0, naiveFetches = 0;
    std::string features; ///< the material's shader features, e.g. "albedo+mask+normal"
};

/// Stage 4: renders `frames` images of `mesh` (a turntable when > 1) with the
/// scene's material, lighting and camera as `request` says, on `context`
/// (null: the CPU reference renderer), and hands each to `sink` as it is
/// done. `cave` must hold the cave view when request.view is "cave".
/// Throws strata::Error for unreadable textures (BadInput) or GL failures.
/// `material` may hold the scene's material already built (buildMaterial(),
/// e.g. to check its maps before anything is written); null: built here.
RenderStats renderSnapshots(const Scene& scene, const meshing::TriangleMesh& mesh, const SnapshotRequest& request,
                            render::GlContext* context, int frames, std::optional<int> width,
                            std::optional<int> height, const std::optional<render::Camera>& cave,
                            const std::function<void(int frame, const render::Image& image)>& sink,
                            const render::Material* material = nullptr);

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
    int threads = 0;                     ///< 0 = all cores; recorded in the report
    /// The memory budget in bytes (0 = no limit): the material's maps
    /// (RGBA8 mip chains, at most render::MAX_MAP_SIZE on a side) count
    /// first, and a grid whose estimated memory exceeds the rest is refused
    /// with the estimate (strata::Error, BadInput) before the long stages.
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
                                            const std::optional<render::Camera>& cave = std::nullopt,
                                            const render::Material* material = nullptr);

/// Meshes `grid` as `quality` says: its mesher (volume with adaptivity, or
/// the chunk meshers in 32³ chunks), normals (grid, face, or `gradient`
/// for "field"), projection steps and simplification (meshoptimizer,
/// borders locked, error bound half a voxel; face normals recomputed).
/// Positions relative to `origin`. `what` receives a short description.
/// Throws strata::Error for "field" normals without a gradient.
meshing::TriangleMesh meshWithQuality(const openvdb::FloatGrid& grid, const QualitySettings& quality,
                                      const meshing::GradientFunction& gradient, const glm::dvec3& origin,
                                      std::string* what = nullptr);

/// Stage 5: report.json — the scene, seed, region, counts, effective quality
/// settings, what the model saved and the stage times. Written atomically.
void writeReport(const GenerateResult& result, const Scene& scene, int threads, const std::filesystem::path& path);

/// Runs the whole pipeline and writes DIR/terrain.vdb, DIR/terrain.glb,
/// (DIR/terrain.ply), DIR/snapshot.png (or .exr; or snapshot_000.png …
/// for a turntable) and DIR/report.json, each atomically.
/// Every input is decoded before the first write: the scene's material maps
/// are loaded and checked (a snapshot needs them; without one, only when the
/// material names map files) before sampling. When a snapshot is requested
/// the snapshot request is checked and the EGL context created first (backend gl: an error without one; auto: the CPU
/// renderer, with a notice), so bad flags write nothing; the cave view is
/// found before any file is written. While it writes, the run holds a lock
/// on the output folder (OutputLock): a second run into the same folder at
/// the same time fails (BadInput) naming the holder. `observer` (may be null) hears the
/// stages and may interrupt. Throws strata::Error on bad input, an
/// unavailable GL context, a failed write or an interruption.
GenerateResult generate(const Scene& scene, const GenerateOptions& options, PipelineObserver* observer = nullptr);

} // namespace strata::scene
