// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Rendering at the extremes, on both renderers (GL through EGL on llvmpipe,
// and the CPU reference): meshes far from the world origin, triplanar
// texturing rebased on a tile-aligned origin, blend and normal settings at
// the limits of their ranges, and degenerate input (zero-area and sliver
// triangles, zero-length normals). Small images (160×90) keep it fast; the
// PSNR of every comparison is printed.

#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>

#include "GoldenScenes.h"
#include "Parity.h"
#include "TestDir.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace strata::render;
using strata::test::TestMesh;

constexpr int WIDTH = 160;
constexpr int HEIGHT = 90;

EglContext& context()
{
    static std::unique_ptr<EglContext> shared = EglContext::create(); // throws (test fails) without EGL
    return *shared;
}

Image render(const std::string& backend, const MeshView& mesh, const SnapshotOptions& options)
{
    return backend == "gl" ? renderSnapshot(context(), mesh, options) : renderSnapshotCpu(mesh, options);
}

void report(const std::string& what, double db)
{
    std::cout << "[ extremes ] " << std::left << std::setw(48) << what << std::right << " PSNR " << std::fixed
              << std::setprecision(2) << db << " dB" << std::defaultfloat << std::endl;
}

/// A ground slab with a sphere on it: every projection shows, with shadows.
TestMesh groundAndSphere()
{
    TestMesh mesh = strata::test::makeBox({-6.0f, -1.0f, -6.0f}, {6.0f, 0.0f, 6.0f});
    const TestMesh sphere = strata::test::makeUvSphere({0.5f, 2.5f, -0.5f}, 2.5f, 32, 16);
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), sphere.positions.begin(), sphere.positions.end());
    mesh.normals.insert(mesh.normals.end(), sphere.normals.begin(), sphere.normals.end());
    for (std::uint32_t i : sphere.indices) mesh.indices.push_back(base + i);
    return mesh;
}

/// The full circuitry material (period 1 / mapScale = 2 m), 160×90, one
/// sample per pixel, the camera framing `mesh` placed at `origin`.
SnapshotOptions optionsAt(const TestMesh& mesh, const glm::dvec3& origin)
{
    SnapshotOptions options = strata::test::goldenOptions(mesh, "full", WIDTH, HEIGHT);
    options.camera.position += origin;
    options.camera.target += origin;
    options.shadows.resolution = 512;
    return options;
}

// ---------------------------------------------------------------------------
// Large worlds: the same mesh far out renders the same image.

class FarOrigin : public ::testing::TestWithParam<std::tuple<std::string, double>>
{
};

// The reference origin is deliberately NOT a multiple of the texture period
// (2 m): the far origin adds a multiple of the period to it, so the texture
// must land on the same texels, which it does only when the texture position
// is rebased on a tile-aligned origin computed in double (in float,
// 1e7 + 3.3 rounds to 10000003 and the texture shifts by 0.3 m).
TEST_P(FarOrigin, MatchesTheRenderNearTheOrigin)
{
    const auto [backend, distance] = GetParam();
    const TestMesh mesh = groundAndSphere();
    const glm::dvec3 nearOrigin(3.3, 1.7, -2.1);
    const glm::dvec3 farOrigin = nearOrigin + glm::dvec3(distance, -distance, distance);

    MeshView nearView = mesh.view();
    nearView.origin = nearOrigin;
    MeshView farView = mesh.view();
    farView.origin = farOrigin;
    const Image nearImage = render(backend, nearView, optionsAt(mesh, nearOrigin));
    const Image farImage = render(backend, farView, optionsAt(mesh, farOrigin));
    const double db = psnr(nearImage, farImage);
    std::ostringstream what;
    what << backend << ": origin offset " << distance << " m vs near the origin";
    report(what.str(), db);
    EXPECT_GE(db, 40.0) << what.str();
    EXPECT_GE(fractionWithin(nearImage, farImage, 2), 0.99) << what.str();
    if (!(db >= 40.0)) {
        const auto dir = strata::test::freshTestDir();
        writeImage(nearImage, dir / "near.png");
        writeImage(farImage, dir / "far.png");
        std::cout << "  wrote " << dir.string() << std::endl;
    }
}

INSTANTIATE_TEST_SUITE_P(Extremes, FarOrigin,
                         ::testing::Combine(::testing::Values(std::string("gl"), std::string("cpu")),
                                            ::testing::Values(1e3, 1e5, 1e7)),
                         [](const auto& info) {
                             const double d = std::get<1>(info.param);
                             return std::get<0>(info.param) + "_1e" + std::to_string(int(std::lround(std::log10(d))));
                         });

// The sky and the height fog far out: the fog's base height is world
// metres (double), made relative to the mesh origin before it reaches the
// shader, so a world 1e7 m away fogs exactly as one at the origin. Dense,
// low fog (density 0.08/m at the base, falloff 0.5/m) so that it visibly
// changes the image; a sky pass too (the camera sees the horizon).
TEST_P(FarOrigin, AtmosphereMatchesTheRenderNearTheOrigin)
{
    const auto [backend, distance] = GetParam();
    const TestMesh mesh = groundAndSphere();
    const glm::dvec3 nearOrigin(3.3, 1.7, -2.1);
    const glm::dvec3 farOrigin = nearOrigin + glm::dvec3(distance, -distance, distance);
    auto foggy = [&](const glm::dvec3& origin) {
        SnapshotOptions options = optionsAt(mesh, origin);
        options.lighting.atmosphere.enabled = true;
        options.lighting.atmosphere.fogDensity = 0.08f;
        options.lighting.atmosphere.fogFalloff = 0.5f;
        options.lighting.atmosphere.fogBaseHeight = origin.y + 0.5;
        options.lighting.sunDirection = glm::vec3(-0.3f, 0.25f, -0.9f); // the glow in view
        return options;
    };
    MeshView nearView = mesh.view();
    nearView.origin = nearOrigin;
    MeshView farView = mesh.view();
    farView.origin = farOrigin;
    const Image nearImage = render(backend, nearView, foggy(nearOrigin));
    const Image farImage = render(backend, farView, foggy(farOrigin));
    const double db = psnr(nearImage, farImage);
    std::ostringstream what;
    what << backend << ": fog and sky at " << distance << " m vs near the origin";
    report(what.str(), db);
    EXPECT_GE(db, 40.0) << what.str();
    EXPECT_GE(fractionWithin(nearImage, farImage, 2), 0.99) << what.str();

    // The fog is there: without the atmosphere most pixels change.
    const Image clear = render(backend, nearView, optionsAt(mesh, nearOrigin));
    const double changed = 1.0 - fractionWithin(nearImage, clear, 8);
    std::cout << "[ extremes ] " << backend << ": the atmosphere changes " << changed * 100.0 << "% of the pixels"
              << std::endl;
    EXPECT_GT(changed, 0.5);
}

// Detail maps repeat detailScale times per base repeat. With a detail scale
// that is not a whole number, an origin that is a whole number of base
// periods need not be a whole number of detail periods, so the detail
// texture position needs its own rebasing (the fraction of the tile-aligned
// origin times the detail scale, in double). The same world surface, meshed
// relative to two origins one base period (2 m) apart, must render the same
// (chunks of a world have different origins and must not show seams);
// without that rebasing the detail pattern jumps by half a detail tile.
TEST_P(FarOrigin, DetailMapsFollowTheWorldWithAFractionalDetailScale)
{
    const auto [backend, distance] = GetParam();
    const TestMesh mesh = groundAndSphere();
    const glm::dvec3 originA(distance, -distance, distance);
    const glm::dvec3 step(2.0, 2.0, -2.0);
    TestMesh shifted = mesh;
    for (glm::vec3& p : shifted.positions) p -= glm::vec3(step);

    SnapshotOptions options = optionsAt(mesh, originA);
    options.material = strata::test::circuitryMaterial("detail-emission");
    options.material.detailScale = 2.5f;
    options.material.detailAlbedo = 1.0f;
    // Close up, so the detail map is not faded out in the small image.
    options.camera.position = options.camera.target + 0.3 * (options.camera.position - options.camera.target);
    options.camera.nearPlane = 0.1;

    MeshView viewA = mesh.view();
    viewA.origin = originA;
    MeshView viewB = shifted.view();
    viewB.origin = originA + step;
    const Image imageA = render(backend, viewA, options);
    const Image imageB = render(backend, viewB, options);
    const double db = psnr(imageA, imageB);
    std::ostringstream what;
    what << backend << ": detail scale 2.5 at " << distance << " m, origins 2 m apart";
    report(what.str(), db);
    EXPECT_GE(db, 40.0) << what.str();

    // The detail map shows: without it the image differs.
    SnapshotOptions plain = options;
    plain.material.detailAlbedo = 0.0f;
    const double changed = 1.0 - fractionWithin(imageA, render(backend, viewA, plain), 1);
    std::cout << "[ extremes ] " << backend << ": the detail map changes " << changed * 100.0 << "% of the pixels"
              << std::endl;
    EXPECT_GT(changed, 0.2);
}

// The texture is tied to the world, not to the mesh's local frame: a mesh
// with origin o renders like the same mesh with o added to its positions and
// a zero origin. Fails if the renderer drops the origin's share of the
// texture position (fract(origin · mapScale)).
class TextureRebasing : public ::testing::TestWithParam<std::string>
{
};

TEST_P(TextureRebasing, FollowsTheWorldNotTheMeshFrame)
{
    const std::string backend = GetParam();
    const TestMesh mesh = groundAndSphere();
    const glm::dvec3 origin(3.3, 1.7, -2.1);
    TestMesh moved = mesh;
    for (glm::vec3& p : moved.positions) p += glm::vec3(origin);

    MeshView local = mesh.view();
    local.origin = origin;
    const SnapshotOptions options = optionsAt(mesh, origin);
    const Image rebased = render(backend, local, options);
    const Image world = render(backend, moved.view(), options);
    const double db = psnr(rebased, world);
    report(backend + ": origin (3.3, 1.7, -2.1) vs the same in the positions", db);
    EXPECT_GE(db, 40.0);

    // And the texture does move with the world: the mesh at a zero origin
    // (no shift of 3.3 m) gives a visibly different image.
    const Image unshifted = render(backend, mesh.view(), optionsAt(mesh, glm::dvec3(0.0)));
    const double shifted = psnr(rebased, unshifted);
    report(backend + ": texture shifted by the origin vs not (must differ)", shifted);
    EXPECT_LT(shifted, 35.0);
}

INSTANTIATE_TEST_SUITE_P(Extremes, TextureRebasing, ::testing::Values(std::string("gl"), std::string("cpu")));

// ---------------------------------------------------------------------------
// Settings at the limits of their ranges, and degenerate meshes.

/// Checks the triplanar weights view: on every pixel the mesh covers (the
/// sky is black), the weights sum to one, so R + G + B = 255 up to rounding
/// (never NaN, never all zero). Returns the number of covered pixels.
int expectWeightsSumToOne(const Image& weights, const std::string& what)
{
    int covered = 0, bad = 0;
    for (int y = 0; y < weights.height; ++y) {
        for (int x = 0; x < weights.width; ++x) {
            const std::uint8_t* p = weights.at(x, y);
            const int sum = p[0] + p[1] + p[2];
            if (sum == 0) continue; // sky
            ++covered;
            if (std::abs(sum - 255) > 3) ++bad;
        }
    }
    EXPECT_EQ(bad, 0) << what << ": pixels whose triplanar weights do not sum to one";
    EXPECT_GT(covered, WIDTH * HEIGHT / 4) << what << ": the mesh covers too little of the image";
    return covered;
}

/// Standard deviation of the image's luminance over the non-sky pixels:
/// a shaded, textured surface is neither black nor flat.
double shadedSpread(const Image& image, const Image& weights)
{
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* w = weights.at(x, y);
            if (w[0] + w[1] + w[2] == 0) continue;
            const std::uint8_t* p = image.at(x, y);
            const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            sum += l;
            sum2 += l * l;
            ++n;
        }
    }
    if (n == 0) return 0.0;
    const double mean = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
}

struct LimitCase
{
    std::string name;
    std::function<void(Material&)> apply;
    /// GL vs CPU PSNR measured on llvmpipe/EGL, AMD EPYC (tests/Parity.h).
    double measuredDb;
};

const std::vector<LimitCase>& limitCases()
{
    static const std::vector<LimitCase> cases = {
        {"blend_offset_0", [](Material& m) { m.blendOffset = 0.0f; }, 58.24},
        {"blend_offset_0_5", [](Material& m) { m.blendOffset = 0.5f; }, 58.09},
        {"blend_exponent_1", [](Material& m) { m.blendExponent = 1.0f; }, 58.33},
        {"blend_exponent_8", [](Material& m) { m.blendExponent = 8.0f; }, 58.13},
        {"height_strength_0", [](Material& m) { m.heightStrength = 0.0f; }, 58.20},
        {"height_strength_0_99", [](Material& m) { m.heightStrength = 0.99f; }, 58.20},
        {"normal_strength_0", [](Material& m) { m.normalStrength = 0.0f; }, 60.09},
        {"normal_strength_2", [](Material& m) { m.normalStrength = 2.0f; }, 55.09},
        {"all_low",
         [](Material& m) {
             m.blendOffset = 0.0f;
             m.blendExponent = 1.0f;
             m.heightStrength = 0.0f;
             m.normalStrength = 0.0f;
         }, 60.32},
        {"all_high",
         [](Material& m) {
             m.blendOffset = 0.5f;
             m.blendExponent = 8.0f;
             m.heightStrength = 0.99f;
             m.normalStrength = 2.0f;
         }, 54.95},
    };
    return cases;
}

class MaterialLimits : public ::testing::TestWithParam<std::size_t>
{
};

// Each limit is legal (checkMaterial accepts it) and gives a finite,
// textured image on both renderers, which agree with each other.
TEST_P(MaterialLimits, FiniteSensibleAndTheSameOnBothRenderers)
{
    const LimitCase& limit = limitCases()[GetParam()];
    const TestMesh mesh = groundAndSphere();
    // The circuitry material with mask (height) and normal maps, every
    // setting mid-range, seen closer so the normal maps show.
    SnapshotOptions baseOptions = strata::test::goldenOptions(mesh, "normal-whiteout", WIDTH, HEIGHT);
    baseOptions.shadows.resolution = 512;
    baseOptions.lighting.skyColor = glm::vec3(0.0f);
    baseOptions.material.blendOffset = 0.25f;
    baseOptions.material.blendExponent = 4.0f;
    baseOptions.material.heightStrength = 0.5f;
    baseOptions.material.normalStrength = 1.0f;
    SnapshotOptions options = baseOptions;
    limit.apply(options.material);
    ASSERT_NO_THROW(checkSnapshotOptions(options)) << limit.name;

    const auto dir = strata::test::freshTestDir();
    std::vector<Image> shaded;
    for (const std::string backend : {"gl", "cpu"}) {
        SnapshotOptions weightsOptions = options;
        weightsOptions.debugView = DebugView::TriplanarWeights;
        const Image weights = render(backend, mesh.view(), weightsOptions);
        expectWeightsSumToOne(weights, backend + " " + limit.name);
        shaded.push_back(render(backend, mesh.view(), options));
        const double spread = shadedSpread(shaded.back(), weights);
        std::cout << "[ extremes ] " << backend << " " << limit.name << ": luminance spread " << spread << std::endl;
        EXPECT_GT(spread, 4.0) << backend << " " << limit.name << ": the shaded surface is flat or black";
        // The limit takes effect: the image differs from the base material's.
        const double changed = 1.0 - fractionWithin(shaded.back(), render(backend, mesh.view(), baseOptions), 1);
        std::cout << "[ extremes ] " << backend << " " << limit.name << ": " << changed * 100.0
                  << "% of the pixels differ from the mid-range material's by more than 1/255" << std::endl;
        EXPECT_GT(changed, 0.001) << backend << " " << limit.name << ": the setting has no visible effect";
        writeImage(shaded.back(), dir / (backend + ".png"));
    }
    const double db = psnr(shaded[0], shaded[1]);
    report("gl vs cpu, " + limit.name, db);
    STRATA_EXPECT_PARITY(db, limit.measuredDb, "limit " + limit.name); // the value in limitCases()
}

INSTANTIATE_TEST_SUITE_P(Extremes, MaterialLimits, ::testing::Range(std::size_t(0), limitCases().size()),
                         [](const auto& info) { return limitCases()[info.param].name; });

class DegenerateMesh : public ::testing::TestWithParam<std::string>
{
};

// Zero-area triangles (three equal vertices, three collinear vertices) and a
// sliver (1e-6 m wide, 10 m long) added to the scene change the image by
// at most the sliver's few pixels; vertices whose normal has length zero
// still shade finitely (weights sum to one, sensible image).
TEST_P(DegenerateMesh, ZeroAreaSliversAndZeroNormalsRenderFinitely)
{
    const std::string backend = GetParam();
    const TestMesh clean = groundAndSphere();
    SnapshotOptions options = optionsAt(clean, glm::dvec3(0.0));
    options.lighting.skyColor = glm::vec3(0.0f);

    TestMesh degenerate = clean;
    auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 n) {
        const auto base = std::uint32_t(degenerate.positions.size());
        for (const glm::vec3& p : {a, b, c}) {
            degenerate.positions.push_back(p);
            degenerate.normals.push_back(n);
        }
        degenerate.indices.insert(degenerate.indices.end(), {base, base + 1, base + 2});
    };
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    add({1.0f, 0.5f, 1.0f}, {1.0f, 0.5f, 1.0f}, {1.0f, 0.5f, 1.0f}, up);           // a point
    add({-2.0f, 0.5f, 2.0f}, {0.0f, 0.5f, 2.0f}, {2.0f, 0.5f, 2.0f}, up);          // collinear
    add({-5.0f, 0.01f, 3.0f}, {5.0f, 0.01f, 3.0f}, {5.0f, 0.01f, 3.000001f}, up); // sliver
    add({-3.0f, 0.5f, -3.0f}, {-3.0f, 0.5f, -3.0f}, {-2.0f, 0.5f, -3.0f}, glm::vec3(0.0f)); // zero area and normal

    SnapshotOptions weightsOptions = options;
    weightsOptions.debugView = DebugView::TriplanarWeights;
    const Image cleanImage = render(backend, clean.view(), options);
    const Image degenerateImage = render(backend, degenerate.view(), options);
    expectWeightsSumToOne(render(backend, degenerate.view(), weightsOptions), backend + " degenerate");
    const double db = psnr(cleanImage, degenerateImage);
    report(backend + ": with zero-area and sliver triangles vs without", db);
    EXPECT_GE(db, 40.0);

    // Zero-length normals on a band of the sphere's vertices.
    TestMesh zeroNormals = clean;
    for (std::size_t i = 24 + 33 * 6; i < 24 + 33 * 10; ++i) zeroNormals.normals[i] = glm::vec3(0.0f);
    const Image weights = render(backend, zeroNormals.view(), weightsOptions);
    expectWeightsSumToOne(weights, backend + " zero normals");
    const Image shaded = render(backend, zeroNormals.view(), options);
    const double spread = shadedSpread(shaded, weights);
    std::cout << "[ extremes ] " << backend << " zero-length normals: luminance spread " << spread << ", PSNR vs clean "
              << psnr(cleanImage, shaded) << " dB" << std::endl;
    EXPECT_GT(spread, 4.0);
    EXPECT_GE(psnr(cleanImage, shaded), 20.0); // a band shades differently, the rest is unchanged
}

INSTANTIATE_TEST_SUITE_P(Extremes, DegenerateMesh, ::testing::Values(std::string("gl"), std::string("cpu")));

} // namespace
