// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The pipeline at the extremes: the scene moved far from the world origin
// (`strata generate --offset`), the same scene scaled from millimetre to
// kilometre voxels, and NaN, infinite, negative and out-of-range values in
// every numeric scene key and in the command-line flags. Small scenes (64
// voxels across) and 160×90 snapshots keep it fast; the numbers are printed.

#include "RunStrata.h"
#include <strata/scene/Scene.h>
#include <strata/scene/SceneOffset.h>
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/render/Image.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/SampleLevelSet.h>

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using strata::test::runStrata;

// 32 × 16 × 32 m at 0.5 m: 64 × 32 × 64 voxels; texture period 8 m
// (map_scale 0.125), so the offsets below are whole periods and voxels.
const char* SMALL_SCENE = "seed = 3\n"
                          "[region]\nmin = [-16.0, -8.0, -16.0]\nmax = [16.0, 8.0, 16.0]\n"
                          "[snapshot]\nwidth = 160\nheight = 90\nsamples = 1\nshadow_resolution = 512\n";

std::filesystem::path writeSmallScene(const std::filesystem::path& dir)
{
    const std::filesystem::path path = dir / "small.toml";
    std::ofstream(path) << SMALL_SCENE;
    return path;
}

std::string offsetText(double d)
{
    std::ostringstream s;
    s << std::setprecision(17) << d << "," << -d << "," << d;
    return s.str();
}

struct MeshMatch
{
    double worstVoxels = 0.0; ///< largest distance of a vertex to its match, voxels
    bool sameTriangles = false; ///< the same triangles through the matching
};

/// Matches each vertex of `b` to the nearest vertex of `a` moved by `offset`
/// (both in world metres, in double; the vertex order may differ, since
/// OpenVDB's node layout moves with the offset) and compares the triangles
/// through that matching.
MeshMatch matchMeshes(const strata::meshing::TriangleMesh& a, const strata::meshing::TriangleMesh& b,
                      const glm::dvec3& offset, double voxelSize)
{
    MeshMatch match;
    if (a.vertexCount() != b.vertexCount() || a.triangleCount() != b.triangleCount()) return match;
    auto cell = [voxelSize](const glm::dvec3& p) {
        const glm::dvec3 c = glm::floor(p / voxelSize);
        return std::array<long long, 3>{(long long)c.x, (long long)c.y, (long long)c.z};
    };
    std::map<std::array<long long, 3>, std::vector<std::uint32_t>> cells;
    std::vector<glm::dvec3> pa(a.vertexCount());
    for (std::size_t i = 0; i < pa.size(); ++i) {
        pa[i] = a.origin + glm::dvec3(a.positions[i]) + offset;
        cells[cell(pa[i])].push_back(std::uint32_t(i));
    }
    std::vector<std::uint32_t> toA(b.vertexCount());
    for (std::size_t i = 0; i < toA.size(); ++i) {
        const glm::dvec3 p = b.origin + glm::dvec3(b.positions[i]);
        const auto c = cell(p);
        double best = HUGE_VAL;
        for (long long dx = -1; dx <= 1; ++dx) {
            for (long long dy = -1; dy <= 1; ++dy) {
                for (long long dz = -1; dz <= 1; ++dz) {
                    const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == cells.end()) continue;
                    for (std::uint32_t j : it->second) {
                        const glm::dvec3 d = glm::abs(pa[j] - p);
                        const double distance = std::max({d.x, d.y, d.z});
                        if (distance < best) {
                            best = distance;
                            toA[i] = j;
                        }
                    }
                }
            }
        }
        match.worstVoxels = std::max(match.worstVoxels, best / voxelSize);
    }
    auto canonical = [](std::array<std::uint32_t, 3> t) {
        while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]}; // rotate, keeping the winding
        return t;
    };
    std::vector<std::array<std::uint32_t, 3>> ta, tb;
    for (std::size_t t = 0; t < a.indices.size(); t += 3) {
        ta.push_back(canonical({a.indices[t], a.indices[t + 1], a.indices[t + 2]}));
        tb.push_back(canonical({toA[b.indices[t]], toA[b.indices[t + 1]], toA[b.indices[t + 2]]}));
    }
    std::sort(ta.begin(), ta.end());
    std::sort(tb.begin(), tb.end());
    match.sameTriangles = ta == tb;
    return match;
}

bool allFinite(const strata::meshing::TriangleMesh& mesh)
{
    for (const glm::vec3& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    }
    for (const glm::vec3& n : mesh.normals) {
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return false;
    }
    return true;
}

// ---------------------------------------------------------------------------
// Large worlds: `strata generate --offset` far out gives the origin's mesh,
// moved, and the origin's snapshot, on both renderers.

class GenerateOffset : public ::testing::TestWithParam<std::string>
{
};

TEST_P(GenerateOffset, MeshAndSnapshotMatchTheOrigins)
{
    const std::string backend = GetParam();
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path scene = writeSmallScene(dir);
    const std::string common = " --size 160x90 -q --backend " + backend;
    const auto reference = runStrata("generate " + scene.string() + " -o " + (dir / "origin").string() + common, dir);
    ASSERT_EQ(reference.exitCode, 0) << reference.output;
    const strata::meshing::TriangleMesh originMesh = strata::meshing::readGltf(dir / "origin" / "terrain.glb");
    const strata::render::Image originImage = strata::render::readImage(dir / "origin" / "snapshot.png");
    ASSERT_GT(originMesh.triangleCount(), 1000u);

    for (const double d : {1e3, 1e5, 1e7}) {
        const std::filesystem::path out = dir / ("offset-" + std::to_string(int(std::lround(std::log10(d)))));
        const auto run =
            runStrata("generate " + scene.string() + " -o " + out.string() + " --offset " + offsetText(d) + common, dir);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        const strata::meshing::TriangleMesh mesh = strata::meshing::readGltf(out / "terrain.glb");
        ASSERT_EQ(mesh.vertexCount(), originMesh.vertexCount()) << d;
        ASSERT_EQ(mesh.triangleCount(), originMesh.triangleCount()) << d;
        EXPECT_TRUE(allFinite(mesh));
        const MeshMatch match = matchMeshes(originMesh, mesh, glm::dvec3(d, -d, d), 0.5);
        EXPECT_TRUE(match.sameTriangles) << d;
        const double voxels = match.worstVoxels;
        const strata::render::Image image = strata::render::readImage(out / "snapshot.png");
        const double db = strata::render::psnr(originImage, image);
        std::cout << "[ extremes ] " << backend << " --offset " << offsetText(d) << ": vertices within " << voxels
                  << " voxel of the origin's moved, snapshot PSNR " << db << " dB" << std::endl;
        EXPECT_LE(voxels, 1e-3) << d;
        EXPECT_GE(db, 40.0) << d;
    }
}

INSTANTIATE_TEST_SUITE_P(Extremes, GenerateOffset, ::testing::Values(std::string("gl"), std::string("cpu")));

/// The linear RGBA floats of an EXR snapshot; empty (and a test failure) if unreadable.
std::vector<float> readExr(const std::filesystem::path& path)
{
    auto input = OIIO::ImageInput::open(path.string());
    if (!input) {
        ADD_FAILURE() << "cannot read " << path << ": " << OIIO::geterror();
        return {};
    }
    const OIIO::ImageSpec& spec = input->spec();
    std::vector<float> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
        ADD_FAILURE() << "cannot read the pixels of " << path;
        return {};
    }
    return pixels;
}

// Every preset, 1e7 m out: no NaN or infinity in the grid, the mesh or the
// (linear float) snapshot, and the same result as at the origin.
TEST(Extremes, EveryPresetFarOutIsFiniteAndMatchesTheOrigin)
{
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path scene = writeSmallScene(dir);
    // (balanced, the scene as written, is GenerateOffset above.)
    for (const std::string preset : {"fast", "accurate"}) {
        std::vector<float> images[2];
        strata::meshing::TriangleMesh meshes[2];
        for (int far = 0; far < 2; ++far) {
            const std::filesystem::path out = dir / (preset + (far ? "-far" : "-origin"));
            const auto run = runStrata("generate " + scene.string() + " -o " + out.string() + " --preset " + preset +
                                           " --backend cpu --size 160x90 --snapshot-format exr -q" +
                                           (far ? " --offset " + offsetText(1e7) : std::string()),
                                       dir);
            ASSERT_EQ(run.exitCode, 0) << run.output;
            const openvdb::FloatGrid::Ptr grid = strata::meshing::readLevelSet(out / "terrain.vdb");
            std::size_t nonFinite = 0;
            for (auto it = grid->cbeginValueAll(); it; ++it) {
                if (!std::isfinite(*it)) ++nonFinite;
            }
            EXPECT_EQ(nonFinite, 0u) << preset;
            meshes[far] = strata::meshing::readGltf(out / "terrain.glb");
            EXPECT_TRUE(allFinite(meshes[far])) << preset;
            images[far] = readExr(out / "snapshot.exr");
            for (const float v : images[far]) {
                if (!std::isfinite(v)) {
                    ADD_FAILURE() << preset << ": a non-finite pixel value";
                    break;
                }
            }
        }
        ASSERT_EQ(meshes[0].vertexCount(), meshes[1].vertexCount()) << preset;
        const double voxelSize = preset == "fast" ? 1.0 : preset == "accurate" ? 0.25 : 0.5; // voxel_scale 2, 1, ½
        const MeshMatch match = matchMeshes(meshes[0], meshes[1], glm::dvec3(1e7, -1e7, 1e7), voxelSize);
        float largest = 0.0f;
        ASSERT_EQ(images[0].size(), images[1].size());
        for (std::size_t i = 0; i < images[0].size(); ++i) {
            largest = std::max(largest, std::abs(images[0][i] - images[1][i]));
        }
        std::cout << "[ extremes ] preset " << preset << " at 1e7 m: " << meshes[1].triangleCount()
                  << " triangles, vertices within " << match.worstVoxels
                  << " voxel (" << voxelSize << " m) of the origin's, largest pixel difference "
                  << largest << " (linear)" << std::endl;
        EXPECT_TRUE(match.sameTriangles) << preset;
        EXPECT_LE(match.worstVoxels, 1e-3) << preset;
        EXPECT_LE(largest, 1.0f / 255.0f) << preset;
    }
}

// `strata render --offset` moves the scene the same way, and with --mesh
// moves the mesh file with it (camera flags are in the scene's coordinates).
TEST(Extremes, RenderOffsetMatchesTheOrigin)
{
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path scene = writeSmallScene(dir);
    const std::string common = " --size 160x90 -q --backend cpu --camera-position 30,25,30 --camera-target 0,-2,0";
    ASSERT_EQ(runStrata("render " + scene.string() + " -o " + (dir / "origin.png").string() + common, dir).exitCode, 0);
    const std::string offset = " --offset " + offsetText(1e7);
    const auto far = runStrata("render " + scene.string() + " -o " + (dir / "far.png").string() + common + offset, dir);
    ASSERT_EQ(far.exitCode, 0) << far.output;
    const strata::render::Image origin = strata::render::readImage(dir / "origin.png");
    const double db = strata::render::psnr(origin, strata::render::readImage(dir / "far.png"));

    // The origin's mesh file, rendered 1e7 m out.
    ASSERT_EQ(runStrata("generate " + scene.string() + " -o " + (dir / "gen").string() + " --no-snapshot -q", dir)
                  .exitCode,
              0);
    const auto mesh = runStrata("render " + scene.string() + " --mesh " + (dir / "gen" / "terrain.glb").string() +
                                    " -o " + (dir / "mesh.png").string() + common + offset,
                                dir);
    ASSERT_EQ(mesh.exitCode, 0) << mesh.output;
    const double meshDb = strata::render::psnr(origin, strata::render::readImage(dir / "mesh.png"));
    std::cout << "[ extremes ] strata render --offset 1e7: PSNR " << db << " dB (scene), " << meshDb
              << " dB (--mesh) against the origin's" << std::endl;
    EXPECT_GE(db, 40.0);
    EXPECT_GE(meshDb, 40.0);
}

// The mesh is kept relative to the region's centre, so its float positions
// stay small however far out the scene is.
TEST(Extremes, FarOutMeshIsStoredRelativeToTheRegion)
{
    strata::scene::Scene scene = strata::scene::offsetScene(strata::scene::parseScene(SMALL_SCENE, "small.toml"),
                                                        glm::dvec3(1e7, -1e7, 1e7));
    EXPECT_EQ(scene.region.min, glm::dvec3(1e7 - 16.0, -1e7 - 8.0, 1e7 - 16.0));
    strata::terrain::SampleOptions sampling;
    sampling.voxelSize = scene.voxelSize;
    sampling.region = scene.region;
    const openvdb::FloatGrid::Ptr grid = strata::terrain::sampleLevelSet(*scene.field, sampling);
    std::size_t nonFinite = 0;
    for (auto it = grid->cbeginValueAll(); it; ++it) {
        if (!std::isfinite(*it)) ++nonFinite;
    }
    EXPECT_EQ(nonFinite, 0u);
    strata::meshing::GridToMeshOptions options;
    options.origin = 0.5 * (scene.region.min + scene.region.max);
    const strata::meshing::TriangleMesh mesh = strata::meshing::gridToMesh(*grid, options);
    ASSERT_GT(mesh.triangleCount(), 0u);
    EXPECT_TRUE(allFinite(mesh));
    float largest = 0.0f;
    for (const glm::vec3& p : mesh.positions) largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    EXPECT_LE(largest, 16.0f + 1e-3f);
}

// ---------------------------------------------------------------------------
// Voxel sizes from 1e-3 m to 1e3 m on the same scene scaled to match.

/// `child` scaled by `s` about the origin: density(p) = s · child(p / s),
/// the same shape s times larger, with the same Lipschitz bound.
class ScaledField final : public strata::terrain::DensityField
{
public:
    ScaledField(std::shared_ptr<const strata::terrain::DensityField> child, double scale)
        : mChild(std::move(child)), mScale(scale)
    {
    }
    double density(const glm::dvec3& p) const override { return mScale * mChild->density(p / mScale); }
    double lipschitz() const override { return mChild->lipschitz(); }
    double minDensity() const override { return mScale * mChild->minDensity(); }
    strata::terrain::Interval bounds(const strata::terrain::WorldBox& box) const override
    {
        const strata::terrain::Interval i = mChild->bounds({box.min / mScale, box.max / mScale});
        return {mScale * i.lo, mScale * i.hi};
    }

private:
    std::shared_ptr<const strata::terrain::DensityField> mChild;
    double mScale;
};

struct ScaledResult
{
    strata::meshing::TriangleMesh mesh;
    strata::meshing::MeshTopology topology;
    double meanError = 0.0; ///< mean |density| at the vertices, in voxels
    double maxError = 0.0;
};

ScaledResult meshAtScale(const std::shared_ptr<const strata::terrain::DensityField>& shape,
                         const strata::terrain::Region& region, double voxelSize, double scale)
{
    const ScaledField field(shape, scale);
    strata::terrain::SampleOptions sampling;
    sampling.voxelSize = voxelSize * scale;
    sampling.region = {region.min * scale, region.max * scale};
    const openvdb::FloatGrid::Ptr grid = strata::terrain::sampleLevelSet(field, sampling);
    for (auto it = grid->cbeginValueAll(); it; ++it) {
        if (!std::isfinite(*it)) ADD_FAILURE() << "non-finite grid value at scale " << scale;
    }
    ScaledResult r;
    r.mesh = strata::meshing::gridToMesh(*grid);
    r.topology = strata::meshing::analyzeTopology(r.mesh);
    double sum = 0.0;
    std::size_t count = 0;
    for (const glm::vec3& p : r.mesh.positions) {
        // The field is 1-Lipschitz: |density| bounds the distance to the exact
        // surface. Vertices on the region's closing faces are not on it.
        const glm::dvec3 w = r.mesh.origin + glm::dvec3(p);
        const glm::dvec3 inside = glm::min(w - sampling.region.min, sampling.region.max - w);
        if (glm::min(inside.x, glm::min(inside.y, inside.z)) < 1.5 * sampling.voxelSize) continue;
        const double e = std::abs(field.density(w)) / sampling.voxelSize;
        sum += e;
        r.maxError = std::max(r.maxError, e);
        ++count;
    }
    r.meanError = count == 0 ? 0.0 : sum / double(count);
    return r;
}

/// A sphere of radius 12 m with a tunnel of radius 4 m through it (genus 1,
/// Euler characteristic 0), and the default terrain's small scene (warped
/// terraces and caves, closed by the region's faces).
struct ScaleCase
{
    std::string name;
    std::shared_ptr<const strata::terrain::DensityField> field;
    strata::terrain::Region region;
};

std::vector<ScaleCase> scaleCases()
{
    using namespace strata::terrain;
    const auto holed = std::make_shared<CsgField>(
        CsgOperation::SUBTRACT,
        std::vector<DensityFieldPtr>{std::make_shared<SphereField>(glm::dvec3(0.5, 0.25, -0.25), 12.0),
                                     std::make_shared<CapsuleField>(glm::dvec3(-20.0, 0.25, -0.25),
                                                                    glm::dvec3(20.0, 0.25, -0.25), 4.0)});
    const strata::scene::Scene scene = strata::scene::parseScene(SMALL_SCENE, "small.toml");
    return {{"holed sphere", holed, {glm::dvec3(-16.0), glm::dvec3(16.0)}}, {"terrain", scene.field, scene.region}};
}

TEST(Extremes, VoxelSizesFromMillimetresToKilometresKeepTopologyAndRelativeError)
{
    const double voxelSize = 0.5;
    for (const ScaleCase& shape : scaleCases()) {
        const ScaledResult unit = meshAtScale(shape.field, shape.region, voxelSize, 1.0);
        ASSERT_GT(unit.mesh.triangleCount(), 1000u);
        const long euler = unit.topology.eulerCharacteristic(); // on vertices welded by position
        if (shape.name == "holed sphere") {
            EXPECT_EQ(euler, 0); // genus 1
            EXPECT_EQ(unit.topology.boundaryEdges, 0u);
            EXPECT_LT(unit.meanError, 0.05); // the exact distance at the vertices, voxels
        }
        for (const double scale : {1e-3, 1e-2, 1e-1, 1e1, 1e2, 1e3}) {
            const ScaledResult r = meshAtScale(shape.field, shape.region, voxelSize, scale);
            EXPECT_TRUE(allFinite(r.mesh)) << scale;
            EXPECT_EQ(r.mesh.vertexCount(), unit.mesh.vertexCount()) << shape.name << " " << scale;
            EXPECT_EQ(r.mesh.triangleCount(), unit.mesh.triangleCount()) << shape.name << " " << scale;
            EXPECT_EQ(r.topology.edges, unit.topology.edges) << shape.name << " " << scale;
            EXPECT_EQ(r.topology.boundaryEdges, unit.topology.boundaryEdges) << shape.name << " " << scale;
            EXPECT_EQ(r.topology.nonManifoldEdges, unit.topology.nonManifoldEdges) << shape.name << " " << scale;
            const long rEuler = r.topology.eulerCharacteristic();
            EXPECT_EQ(rEuler, euler) << shape.name << " " << scale;
            // The same vertices, scaled: within 1e-3 voxel.
            double worst = 0.0;
            if (r.mesh.vertexCount() == unit.mesh.vertexCount()) {
                for (std::size_t i = 0; i < r.mesh.positions.size(); ++i) {
                    const glm::dvec3 d = glm::abs((r.mesh.origin + glm::dvec3(r.mesh.positions[i])) / scale -
                                                  (unit.mesh.origin + glm::dvec3(unit.mesh.positions[i])));
                    worst = std::max({worst, d.x, d.y, d.z});
                }
            }
            worst /= voxelSize;
            std::cout << "[ extremes ] " << shape.name << ", voxel size " << voxelSize * scale << " m: "
                      << r.mesh.vertexCount() << " vertices, " << r.mesh.triangleCount()
                      << " triangles, Euler characteristic " << rEuler << ", " << r.topology.boundaryEdges
                      << " boundary edges; vertices within " << worst << " voxel of the 0.5 m mesh scaled";
            if (shape.name == "holed sphere") {
                std::cout << "; distance to the exact surface mean " << r.meanError << ", max " << r.maxError
                          << " voxel (0.5 m: " << unit.meanError << ", " << unit.maxError << ")";
            }
            std::cout << std::endl;
            EXPECT_LE(worst, 1e-3) << shape.name << " " << scale;
            if (shape.name == "holed sphere") {
                EXPECT_NEAR(r.meanError, unit.meanError, 1e-3 * unit.meanError + 1e-5) << scale;
                EXPECT_NEAR(r.maxError, unit.maxError, 1e-3 * unit.maxError + 1e-5) << scale;
            }
        }
    }
}

// ---------------------------------------------------------------------------
// NaN, infinity, negative and out-of-range values: every numeric scene key.

struct KeyCase
{
    std::string table; ///< "" for the top level, "light.extra" for [[light.extra]]
    std::string key;
    bool vector;        ///< a 3-element array
    bool negativeLegal; ///< -1 is a legal value
};

const std::vector<KeyCase>& numericKeys()
{
    static const std::vector<KeyCase> keys = {
        {"", "seed", false, false},
        {"region", "min", true, true},
        {"region", "max", true, true},
        {"sampling", "voxel_size", false, false},
        {"sampling", "half_width", false, false},
        {"terrain.height", "base", false, true},
        {"terrain.height", "amplitude", false, false},
        {"terrain.height", "wavelength", false, false},
        {"terrain.height", "octaves", false, false},
        {"terrain.height", "lacunarity", false, false},
        {"terrain.height", "gain", false, false},
        {"terrain.caves", "wavelength", false, false},
        {"terrain.caves", "radius", false, false},
        {"terrain.caves", "octaves", false, false},
        {"terrain.caves", "vertical_squash", false, false},
        {"terrain.caves", "max_height", false, true},
        {"mesh", "adaptivity", false, false},
        {"material", "map_scale", false, false},
        {"material", "blend_offset", false, false},
        {"material", "blend_exponent", false, false},
        {"material", "height_strength", false, false},
        {"material", "texture_size", false, false},
        {"material", "texture_seed", false, false},
        {"material", "normal_strength", false, false},
        {"material", "occlusion_strength", false, false},
        {"material", "metallic", false, false},
        {"material", "smoothness", false, false},
        {"material", "fresnel_strength", false, false},
        {"material", "detail_scale", false, false},
        {"material", "detail_albedo", false, false},
        {"material", "detail_smoothness", false, false},
        {"material", "detail_normal_strength", false, false},
        {"material", "detail_fade_start", false, false},
        {"material", "detail_fade_end", false, false},
        {"material", "emission_color", true, false},
        {"material", "albedo_tint", true, false},
        {"camera", "azimuth", false, true},
        {"camera", "elevation", false, true},
        {"camera", "zoom", false, false},
        {"camera", "fov", false, false},
        {"camera", "position", true, true},
        {"camera", "target", true, true},
        {"light", "sun_azimuth", false, true},
        {"light", "sun_elevation", false, true},
        {"light", "sun_color", true, false},
        {"light", "exposure", false, false},
        {"light.extra", "azimuth", false, true},
        {"light.extra", "elevation", false, true},
        {"light.extra", "color", true, false},
        {"snapshot", "width", false, false},
        {"snapshot", "height", false, false},
        {"snapshot", "samples", false, false},
        {"snapshot", "anisotropy", false, false},
        {"snapshot", "shadow_resolution", false, false},
        {"snapshot", "shadow_normal_bias", false, false},
        {"snapshot", "shadow_depth_bias", false, false},
    };
    return keys;
}

/// The scene text setting `key` to `value` (in the first element for an array).
std::string sceneWith(const KeyCase& k, const std::string& value)
{
    const std::string v = k.vector ? "[" + value + ", 1.0, 1.0]" : value;
    // An explicit camera needs both ends; a region needs max > min.
    std::string text;
    if (k.table.empty()) return k.key + " = " + v + "\n";
    if (k.table == "light.extra") return "[[light.extra]]\n" + k.key + " = " + v + "\n";
    text = "[" + k.table + "]\n" + k.key + " = " + v + "\n";
    return text;
}

std::string qualified(const KeyCase& k)
{
    if (k.table.empty()) return k.key;
    if (k.table == "light.extra") return "light.extra[0]." + k.key;
    return k.table + "." + k.key;
}

TEST(Extremes, EveryNumericSceneKeyRejectsNanAndInfinityNamingTheKey)
{
    int checked = 0;
    for (const KeyCase& k : numericKeys()) {
        // (1e999 overflows: a TOML syntax error, naming the file and line.)
        std::vector<std::string> bad = {"nan", "inf", "-inf", "1e999"};
        if (!k.negativeLegal) bad.push_back("-1");
        if (!k.negativeLegal && !k.vector) bad.push_back("1e300");
        for (const std::string& value : bad) {
            const std::string text = sceneWith(k, value);
            try {
                (void)strata::scene::parseScene(text, "bad.toml");
                ADD_FAILURE() << qualified(k) << " = " << value << " was accepted";
            } catch (const strata::Error& e) {
                const std::string message = e.what();
                EXPECT_NE(message.find("bad.toml:"), std::string::npos) << message;
                const std::string where = value == "1e999" ? "bad.toml:" + std::to_string(k.table.empty() ? 1 : 2)
                                                           : qualified(k);
                EXPECT_NE(message.find(where), std::string::npos) << qualified(k) << " = " << value << ": " << message;
            }
            ++checked;
        }
    }
    std::cout << "[ extremes ] " << checked << " bad values in " << numericKeys().size()
              << " numeric scene keys: each rejected, naming its key" << std::endl;
}

// The legal limits of the blend and normal settings are accepted.
TEST(Extremes, BlendAndNormalLimitsAreLegalInTheSceneFile)
{
    for (const char* line :
         {"blend_offset = 0.0", "blend_offset = 0.5", "blend_exponent = 1.0", "blend_exponent = 8.0",
          "height_strength = 0.0", "height_strength = 0.99", "normal_strength = 0.0", "normal_strength = 2.0"}) {
        EXPECT_NO_THROW((void)strata::scene::parseScene(std::string("[material]\n") + line + "\n", "limits.toml")) << line;
    }
}

// Through the executable: exit code 2, one line naming the key or flag and
// the value, and nothing written (the output folder is not even created).
TEST(Extremes, BadValuesExitWithTwoAndWriteNothing)
{
    const auto dir = strata::test::freshTestDir();
    struct Case
    {
        std::string scene; ///< scene text, or "" for the small scene
        std::string flags;
        std::string expected; ///< part of the message
        bool render = false; ///< also through `strata render` (same flag and scene code)
    };
    const std::vector<Case> cases = {
        {"[sampling]\nvoxel_size = nan\n", "", "sampling.voxel_size", true},
        {"[sampling]\nvoxel_size = -1.0\n", "", "sampling.voxel_size"},
        {"[material]\nblend_exponent = inf\n", "", "material.blend_exponent"},
        {"[camera]\nposition = [1.0, nan, 1.0]\ntarget = [0.0, 0.0, 0.0]\n", "", "camera.position"},
        {"[light]\nsun_color = [1.0, -1.0, 1.0]\n", "", "light.sun_color"},
        {"[region]\nmin = [-inf, 0.0, 0.0]\n", "", "region.min"},
        {"", "--offset nan,0,0", "--offset 'nan,0,0'", true},
        {"", "--offset 0,inf,0", "--offset '0,inf,0'"},
        {"", "--offset 1e400,0,0", "--offset '1e400,0,0'", true},
        {"", "--offset 2e9,0,0", "--offset '2e9,0,0'"},
        {"", "--offset 6e8,0,0", "--offset '6e+08,0,0' moves the region beyond what voxel_size", true},
        {"", "--offset=-1,2", "--offset '-1,2'"},
        {"", "--offset x,y,z", "--offset 'x,y,z'"},
        {"", "--seed -1", "--seed", true},
        {"", "--seed 18446744073709551616", "'18446744073709551616' is not a seed", true},
        {"", "--seed 9223372036854775808", "'9223372036854775808' is not a seed"},
        {"", "--seed 12abc", "'12abc' is not a seed"},
        {"", "--no-such-flag", "strata: error: The following argument was not expected: --no-such-flag"},
        {"", "--fov nan", "--fov 'nan'"},
        {"", "--fov -1", "--fov"},
        {"", "--camera-position inf,0,0", "--camera-position 'inf,0,0'"},
        {"", "--max-memory nan", "--max-memory 'nan'"},
        {"", "--size 0x90", "--size '0x90'"},
    };
    int i = 0;
    for (const Case& c : cases) {
        const std::filesystem::path scene = dir / ("case" + std::to_string(i) + ".toml");
        std::ofstream(scene) << (c.scene.empty() ? SMALL_SCENE : c.scene);
        for (const std::string command : {"generate", "render"}) {
            if (!c.render && command == std::string("render")) continue;
            const std::filesystem::path out = dir / ("out" + std::to_string(i) + "-" + command);
            const std::string target = command == std::string("generate") ? out.string() : (out / "image.png").string();
            const auto run = runStrata(std::string(command) + " " + scene.string() + " -o " + target +
                                           " --backend cpu -q " + c.flags,
                                       dir);
            EXPECT_EQ(run.exitCode, 2) << command << " " << c.flags << " " << c.scene << run.output;
            EXPECT_NE(run.output.find(c.expected), std::string::npos) << command << ": " << run.output;
            EXPECT_FALSE(std::filesystem::exists(out)) << command << " " << c.flags << " wrote " << out;
        }
        ++i;
    }
}

} // namespace
