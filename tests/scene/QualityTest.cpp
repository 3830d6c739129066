// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Quality presets and knobs (apps/strata/Quality.h): the preset table,
// precedence, scene-file and flag errors, and `strata generate` applying each
// knob end to end.

#include <strata/scene/Quality.h>
#include "RunStrata.h"
#include "Parity.h"
#include <strata/scene/Scene.h>
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/render/Image.h>
#include <strata/render/Texture.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using namespace strata::scene;

namespace {

using strata::test::CommandResult;
using strata::test::runStrata;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Every effective setting as text, to see which ones a change touched.
std::map<std::string, std::string> fields(const QualitySettings& q)
{
    std::ostringstream voxel;
    voxel << q.voxelSize;
    return {{"voxel", voxel.str()},
            {"half_width", std::to_string(q.halfWidth)},
            {"mesher", q.mesher},
            {"adaptivity", std::to_string(q.adaptivity)},
            {"normals", q.normals},
            {"projection", std::to_string(q.projectionSteps)},
            {"simplify", std::to_string(q.simplifyRatio)},
            {"filtering", filteringName(q.filtering)},
            {"normal_blend", normalBlendName(q.normalBlend)},
            {"projections", std::to_string(q.projections)},
            {"anti_tiling", q.antiTiling ? "on" : "off"},
            {"shadow_resolution", std::to_string(q.shadowResolution)},
            {"backend", q.backend}};
}

std::vector<std::string> changed(const QualitySettings& a, const QualitySettings& b)
{
    std::vector<std::string> out;
    const auto fa = fields(a), fb = fields(b);
    for (const auto& [key, value] : fa) {
        if (fb.at(key) != value) out.push_back(key);
    }
    return out;
}

std::string errorOf(const std::string& toml)
{
    try {
        parseScene(toml, "test.toml");
    } catch (const strata::Error& e) {
        return e.what();
    }
    return "";
}

nlohmann::json readJson(const std::filesystem::path& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

// A small scene: generate runs in well under a second per preset.
std::filesystem::path smallScene(const std::filesystem::path& dir, const std::string& extra = "")
{
    const std::filesystem::path path = dir / "scene.toml";
    std::ofstream(path) << "seed = 3\n[region]\nmin = [-12.0, -10.0, -12.0]\nmax = [12.0, 10.0, 12.0]\n"
                           "[material]\ntexture_size = 64\n[snapshot]\nwidth = 96\nheight = 64\nsamples = 1\n"
                        << extra;
    return path;
}

} // namespace

TEST(Quality, PresetTable)
{
    EXPECT_EQ(presetNames(), (std::vector<std::string>{"fast", "balanced", "accurate"}));
    EXPECT_TRUE(presetKnobs("balanced").empty()); // balanced is the scene as written
    const QualityOverrides fast = presetKnobs("fast"), accurate = presetKnobs("accurate");
    EXPECT_EQ(fast.at("voxel_scale"), "2");
    EXPECT_EQ(accurate.at("voxel_scale"), "0.5");
    for (const auto& [key, value] : fast) EXPECT_EQ(checkKnob(key, value), value) << key;
    for (const auto& [key, value] : accurate) EXPECT_EQ(checkKnob(key, value), value) << key;
    try {
        presetKnobs("ultra");
        FAIL() << "no error";
    } catch (const strata::Error& e) {
        EXPECT_TRUE(contains(e.what(), "'ultra'")) << e.what();
        EXPECT_TRUE(contains(e.what(), "fast, balanced or accurate")) << e.what();
    }
}

TEST(Quality, BalancedIsTheSceneAsWritten)
{
    const Scene scene = parseScene("[sampling]\nvoxel_size = 0.7\nhalf_width = 5\n[mesh]\nadaptivity = 0.25\n"
                                   "[snapshot]\nshadow_resolution = 512\n[material]\nnormal_blend = \"udn\"\n",
                                   "test.toml");
    const QualitySettings q = resolveQuality(scene, std::nullopt, {});
    EXPECT_EQ(q.preset, "balanced");
    EXPECT_DOUBLE_EQ(q.voxelSize, 0.7);
    EXPECT_EQ(q.halfWidth, 5);
    EXPECT_DOUBLE_EQ(q.adaptivity, 0.25);
    EXPECT_EQ(q.shadowResolution, 512);
    EXPECT_EQ(q.normalBlend, strata::render::NormalBlend::Udn);
    EXPECT_EQ(q.mesher, "volume");
    EXPECT_EQ(q.normals, "grid");
    EXPECT_EQ(q.projectionSteps, 0);
    EXPECT_DOUBLE_EQ(q.simplifyRatio, 1.0);
    EXPECT_EQ(q.filtering, strata::render::TextureFilter::Trilinear);
    EXPECT_EQ(q.backend, "auto");
    const Scene applied = applyQuality(scene, q);
    EXPECT_DOUBLE_EQ(applied.voxelSize, 0.7);
    EXPECT_EQ(applied.snapshot.shadows.resolution, 512);
}

TEST(Quality, PresetsDifferAsDocumented)
{
    const Scene scene = parseScene("", "test.toml");
    const QualitySettings fast = resolveQuality(scene, "fast", {});
    const QualitySettings balanced = resolveQuality(scene, "balanced", {});
    const QualitySettings accurate = resolveQuality(scene, "accurate", {});
    EXPECT_DOUBLE_EQ(fast.voxelSize, 2.0 * scene.voxelSize);
    EXPECT_DOUBLE_EQ(accurate.voxelSize, 0.5 * scene.voxelSize);
    EXPECT_EQ(fast.mesher, "surface-nets");
    EXPECT_EQ(fast.filtering, strata::render::TextureFilter::Bilinear);
    EXPECT_EQ(fast.projections, 2); // biplanar
    EXPECT_EQ(accurate.projections, 3);
    EXPECT_EQ(applyQuality(scene, fast).material.parameters.projections, 2);
    EXPECT_FALSE(fast.antiTiling);
    EXPECT_LT(fast.simplifyRatio, 1.0);
    EXPECT_LT(fast.shadowResolution, balanced.shadowResolution);
    EXPECT_GT(accurate.shadowResolution, balanced.shadowResolution);
    EXPECT_EQ(accurate.normals, "field");
    EXPECT_GT(accurate.projectionSteps, 0);
    EXPECT_EQ(accurate.normalBlend, strata::render::NormalBlend::Rnm);
    EXPECT_GE(changed(fast, balanced).size(), 6u);
    EXPECT_GE(changed(accurate, balanced).size(), 6u);
}

TEST(Quality, EachOverrideChangesExactlyItsKnob)
{
    const Scene scene = parseScene("", "test.toml");
    const QualitySettings balanced = resolveQuality(scene, std::nullopt, {});
    const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> cases = {
        {"voxel_size", {"0.3", "voxel"}},        {"voxel_scale", {"2", "voxel"}},
        {"half_width", {"6", "half_width"}},     {"mesher", {"dual-contouring", "mesher"}},
        {"adaptivity", {"0.5", "adaptivity"}},   {"normals", {"face", "normals"}},
        {"projection", {"3", "projection"}},     {"simplify", {"0.25", "simplify"}},
        {"filtering", {"bilinear", "filtering"}}, {"normal_blend", {"rnm", "normal_blend"}},
        {"shadow_resolution", {"512", "shadow_resolution"}}, {"backend", {"cpu", "backend"}},
        {"projections", {"2", "projections"}},   {"anti_tiling", {"on", "anti_tiling"}},
    };
    ASSERT_EQ(cases.size(), qualityKeys().size()); // every knob is covered
    for (const auto& [key, valueAndField] : cases) {
        QualityOverrides flags;
        addQualityFlag(key + "=" + valueAndField.first, flags);
        const QualitySettings q = resolveQuality(scene, std::nullopt, flags);
        EXPECT_EQ(changed(q, balanced), std::vector<std::string>{valueAndField.second}) << key;
    }
}

TEST(Quality, FlagBeatsQualityKeyBeatsPreset)
{
    const Scene scene = parseScene("[quality]\npreset = \"fast\"\nmesher = \"dual-contouring\"\nshadow_resolution = 300\n",
                                   "test.toml");
    ASSERT_TRUE(scene.quality.preset.has_value());
    // The scene's preset, its keys on top.
    QualitySettings q = resolveQuality(scene, std::nullopt, {});
    EXPECT_EQ(q.preset, "fast");
    EXPECT_DOUBLE_EQ(q.voxelSize, 2.0 * scene.voxelSize); // from the preset
    EXPECT_EQ(q.mesher, "dual-contouring");                // [quality] key beats the preset's surface-nets
    EXPECT_EQ(q.shadowResolution, 300);
    // --preset beats [quality] preset; the [quality] keys still win over it.
    q = resolveQuality(scene, "accurate", {});
    EXPECT_EQ(q.preset, "accurate");
    EXPECT_DOUBLE_EQ(q.voxelSize, 0.5 * scene.voxelSize);
    EXPECT_EQ(q.mesher, "dual-contouring");
    EXPECT_EQ(q.shadowResolution, 300);
    // A flag beats the [quality] key.
    QualityOverrides flags;
    addQualityFlag("mesher=volume", flags);
    addQualityFlag("voxel_size=0.8", flags);
    q = resolveQuality(scene, std::nullopt, flags);
    EXPECT_EQ(q.mesher, "volume");
    EXPECT_DOUBLE_EQ(q.voxelSize, 0.8);
    EXPECT_EQ(q.shadowResolution, 300);
}

TEST(Quality, SceneFileErrorsNameFileLineAndKey)
{
    EXPECT_TRUE(contains(errorOf("[quality]\npreset = \"ultra\"\n"), "test.toml:2: quality.preset = 'ultra'"));
    EXPECT_TRUE(contains(errorOf("[quality]\nmesher = \"marching\"\n"), "test.toml:2: quality.mesher = 'marching'"));
    EXPECT_TRUE(contains(errorOf("[quality]\n\nvoxels = 1.0\n"), "test.toml:3: unknown key 'quality.voxels'"));
    EXPECT_TRUE(contains(errorOf("[quality]\nvoxel_size = nan\n"), "quality.voxel_size = nan must be finite"));
    EXPECT_TRUE(contains(errorOf("[quality]\nvoxel_size = inf\n"), "quality.voxel_size = inf must be finite"));
    EXPECT_TRUE(contains(errorOf("[quality]\nsimplify = 0.0\n"), "quality.simplify = 0 is out of range"));
    EXPECT_TRUE(contains(errorOf("[quality]\nadaptivity = -0.5\n"), "quality.adaptivity = -0.5 is out of range"));
    EXPECT_TRUE(contains(errorOf("[quality]\nprojection = 1.5\n"), "quality.projection = 1.5 must be an integer"));
    EXPECT_TRUE(contains(errorOf("[quality]\nfiltering = 3\n"), "quality.filtering = 3 must be a string"));
    EXPECT_TRUE(contains(errorOf("[quality]\nvoxel_size = 0.5\nvoxel_scale = 2\n"),
                         "quality.voxel_scale cannot be combined with quality.voxel_size"));
    EXPECT_EQ(errorOf("[quality]\npreset = \"accurate\"\nfiltering = \"bilinear\"\nbackend = \"cpu\"\n"), "");
}

TEST(Quality, FlagErrorsNameKeyAndValue)
{
    auto flagError = [](const std::string& text) -> std::string {
        QualityOverrides o;
        try {
            addQualityFlag(text, o);
        } catch (const strata::Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_TRUE(contains(flagError("mesher"), "--quality 'mesher' must look like KEY=VALUE"));
    EXPECT_TRUE(contains(flagError("voxels=1"), "unknown quality key 'voxels'"));
    EXPECT_TRUE(contains(flagError("voxel_size=inf"), "voxel_size = 'inf' must be finite"));
    EXPECT_TRUE(contains(flagError("voxel_size=nan"), "voxel_size = 'nan' must be finite"));
    EXPECT_TRUE(contains(flagError("voxel_size=-1"), "voxel_size = '-1' is out of range"));
    EXPECT_TRUE(contains(flagError("simplify=0"), "simplify = '0' is out of range"));
    EXPECT_TRUE(contains(flagError("projection=1.5"), "projection = '1.5' must be an integer"));
    EXPECT_TRUE(contains(flagError("half_width=2"), "half_width = '2' is out of range [3, 32]"));
    EXPECT_TRUE(contains(flagError("shadow_resolution=abc"), "shadow_resolution = 'abc' must be a number"));
    EXPECT_TRUE(contains(flagError("backend=vulkan"), "backend = 'vulkan' must be auto, gl or cpu"));
    EXPECT_EQ(flagError("normals=field"), "");
    QualityOverrides both;
    addQualityFlag("voxel_size=0.5", both);
    EXPECT_THROW(addQualityFlag("voxel_scale=2", both), strata::Error);
}

TEST(Quality, GenerateBadPresetOrValueExitsTwoAndWritesNothing)
{
    STRATA_REQUIRE_PROGRAM();
    const auto dir = strata::test::freshTestDir();
    const std::string scene = smallScene(dir).string();
    for (const std::string& flags : {std::string("--preset ultra"), std::string("--quality mesher=marching"),
                                     std::string("--quality voxel_size=nan"), std::string("--quality simplify=2")}) {
        const std::filesystem::path out = dir / "out";
        const CommandResult run = runStrata("generate " + scene + " -o " + out.string() + " " + flags, dir);
        EXPECT_EQ(run.exitCode, 2) << flags << "\n" << run.output;
        const std::string value = flags.substr(flags.find_first_of(" =") + 1);
        EXPECT_TRUE(contains(run.output, value.substr(value.find('=') + 1))) << flags << "\n" << run.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << flags;
    }
    // A bad [quality] value in the scene file: the same.
    const std::string bad = smallScene(dir, "[quality]\nnormals = \"smooth\"\n").string();
    const CommandResult run = runStrata("generate " + bad + " -o " + (dir / "out").string(), dir);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_TRUE(contains(run.output, "quality.normals = 'smooth'")) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST(Quality, GenerateAppliesPresetsAndOverrides)
{
    STRATA_REQUIRE_PROGRAM();
    const auto dir = strata::test::freshTestDir();
    const std::string scene = smallScene(dir).string();
    std::map<std::string, nlohmann::json> reports;
    for (const std::string name : {"fast", "balanced", "accurate"}) {
        const std::filesystem::path out = dir / name;
        const CommandResult run = runStrata("generate " + scene + " -o " + out.string() + " --no-snapshot --preset " + name, dir);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        EXPECT_TRUE(contains(run.output, "quality   preset " + name)) << run.output;
        reports[name] = readJson(out / "report.json");
        EXPECT_EQ(reports[name]["quality"]["preset"], name);
    }
    const auto voxels = [&](const std::string& n) { return reports[n]["active_voxels"].get<std::uint64_t>(); };
    const auto triangles = [&](const std::string& n) { return reports[n]["triangles"].get<std::uint64_t>(); };
    EXPECT_LT(voxels("fast"), voxels("balanced"));
    EXPECT_LT(voxels("balanced"), voxels("accurate"));
    EXPECT_LT(triangles("fast"), triangles("balanced"));
    EXPECT_LT(triangles("balanced"), triangles("accurate"));
    EXPECT_DOUBLE_EQ(reports["fast"]["voxel_size"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(reports["accurate"]["voxel_size"].get<double>(), 0.25);
    EXPECT_EQ(reports["fast"]["quality"]["mesher"], "surface-nets");
    EXPECT_EQ(reports["accurate"]["quality"]["normals"], "field");

    // One override on balanced: sampling untouched, only the mesh changes.
    const CommandResult run = runStrata("generate " + scene + " -o " + (dir / "sn").string() +
                                            " --no-snapshot --quality simplify=0.5",
                                        dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json simplified = readJson(dir / "sn" / "report.json");
    EXPECT_EQ(simplified["active_voxels"], reports["balanced"]["active_voxels"]);
    EXPECT_EQ(simplified["evaluated_points"], reports["balanced"]["evaluated_points"]);
    EXPECT_LT(simplified["triangles"].get<std::uint64_t>(), triangles("balanced"));
    nlohmann::json expected = reports["balanced"]["quality"];
    expected["simplify"] = 0.5;
    EXPECT_EQ(simplified["quality"], expected);
}

TEST(Quality, ReportMeasuresWhatTheSceneRequires)
{
    STRATA_REQUIRE_PROGRAM();
    const auto dir = strata::test::freshTestDir();
    const std::string scene = smallScene(dir).string();
    CommandResult run = runStrata("generate " + scene + " -o " + (dir / "cpu").string() + " --backend cpu", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json cpu = readJson(dir / "cpu" / "report.json")["model"];
    EXPECT_GT(cpu["evaluated_points"].get<std::uint64_t>(), 0u);
    EXPECT_GT(cpu["active_voxels"].get<std::uint64_t>(), 0u);
    const std::uint64_t done = cpu["texture_fetches"], naive = cpu["texture_fetches_naive"];
    EXPECT_GT(cpu["shaded_pixels"].get<std::uint64_t>(), 0u);
    EXPECT_GT(done, 0u);
    EXPECT_LT(done, naive); // zero-weight projections are skipped
    EXPECT_EQ(cpu["texture_fetches_skipped"].get<std::uint64_t>(), naive - done);
    // Each shaded pixel reads at least one projection of the albedo.
    EXPECT_GE(done, cpu["shaded_pixels"].get<std::uint64_t>());
    EXPECT_TRUE(contains(run.output, "texture fetches of")) << run.output;

    run = runStrata("generate " + scene + " -o " + (dir / "gl").string() + " --backend auto", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json report = readJson(dir / "gl" / "report.json");
    // Never skipped: --backend auto fell back to the CPU only without an EGL
    // context (Mesa llvmpipe, installed by scripts/install-deps.sh).
    ASSERT_NE(report["renderer"], "strata CPU reference renderer")
        << "no OpenGL context: the EGL tests need one (Mesa's libegl-mesa0 and libgl1-mesa-dri)\n" << run.output;
    EXPECT_EQ(report["model"]["shader_variants_compiled"], 1);
    EXPECT_EQ(report["model"]["shader_variants_possible"], 1680);
    EXPECT_TRUE(contains(run.output, "1 of 1680 shader variants compiled")) << run.output;
}

TEST(Quality, BilinearFilteringMatchesOnBothRenderersAndDiffersFromTrilinear)
{
    STRATA_REQUIRE_PROGRAM();
    const auto dir = strata::test::freshTestDir();
    const std::string scene = smallScene(dir).string();
    auto render = [&](const std::string& name, const std::string& flags) {
        const CommandResult run =
            runStrata("generate " + scene + " -o " + (dir / name).string() + " --size 160x96 " + flags, dir);
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return readJson(dir / name / "report.json");
    };
    render("cpu-bilinear", "--backend cpu --quality filtering=bilinear");
    render("cpu-trilinear", "--backend cpu");
    const strata::render::Image bilinear = strata::render::readImage(dir / "cpu-bilinear" / "snapshot.png");
    const strata::render::Image trilinear = strata::render::readImage(dir / "cpu-trilinear" / "snapshot.png");
    const double change = strata::render::psnr(bilinear, trilinear);
    EXPECT_LT(change, 200.0); // different images
    EXPECT_GT(change, 25.0);  // of the same scene
    const nlohmann::json gl = render("gl-bilinear", "--backend auto --quality filtering=bilinear");
    ASSERT_NE(gl["renderer"], "strata CPU reference renderer") << "no OpenGL context (CI has EGL on llvmpipe)";
    EXPECT_EQ(gl["quality"]["filtering"], "bilinear");
    const strata::render::Image glBilinear = strata::render::readImage(dir / "gl-bilinear" / "snapshot.png");
    // One sample per pixel on both: the same filtering gives nearly the same image.
    // Measured 55.24 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(strata::render::psnr(glBilinear, bilinear), 55.24, "bilinear, 160x96");
    EXPECT_GT(strata::render::psnr(glBilinear, bilinear), strata::render::psnr(glBilinear, trilinear));
}

TEST(Quality, RenderAppliesTheScenesQualityTable)
{
    STRATA_REQUIRE_PROGRAM();
    const auto dir = strata::test::freshTestDir();
    const std::string plain = smallScene(dir).string();
    std::filesystem::create_directories(dir / "q");
    const std::string bilinear = smallScene(dir / "q", "[quality]\nfiltering = \"bilinear\"\n").string();
    auto run = [&](const std::string& command) {
        const CommandResult result = runStrata(command + " --backend cpu --size 160x96", dir);
        EXPECT_EQ(result.exitCode, 0) << result.output;
    };
    run("render " + bilinear + " -o " + (dir / "render-bilinear.png").string());
    run("render " + plain + " -o " + (dir / "render-trilinear.png").string());
    run("generate " + bilinear + " -o " + (dir / "generate-bilinear").string());
    const auto image = [&](const std::filesystem::path& path) { return strata::render::readImage(dir / path); };
    // render and generate draw the same scene with the same settings: the same bytes.
    EXPECT_EQ(image("render-bilinear.png").pixels, image(std::filesystem::path("generate-bilinear") / "snapshot.png").pixels);
    EXPECT_NE(image("render-bilinear.png").pixels, image("render-trilinear.png").pixels);
}

TEST(Quality, BilinearSamplerPicksGlsNearestMipLevel)
{
    // A 16×16 texture whose levels are constant 0, 50, 100, 150, 200 (R):
    // the level read is visible in the value.
    strata::render::Texture texture;
    texture.kind = strata::render::MapKind::Mask;
    texture.srgb = false;
    for (int level = 0, size = 16; size >= 1; ++level, size /= 2) {
        strata::render::Texture::Level l;
        l.width = l.height = size;
        l.texels.assign(std::size_t(size * size * 4), std::uint8_t(50 * level));
        texture.levels.push_back(l);
    }
    ASSERT_EQ(texture.levels.size(), 5u);
    // λ = log2(16 · |dUV|) for a derivative along u only; powers of two are exact.
    auto at = [&](float lambda, bool bilinear) {
        const glm::vec2 d(std::exp2(lambda) / 16.0f, 0.0f);
        const glm::vec4 v = bilinear ? strata::render::sampleBilinearNearestMip(texture, {0.3f, 0.6f}, d, d)
                                     : strata::render::sampleTrilinear(texture, {0.3f, 0.6f}, d, d);
        return v.r * 255.0f / 50.0f; // the level (or blend of levels) read
    };
    EXPECT_NEAR(at(-2.0f, true), 0.0f, 1e-5f); // magnification
    EXPECT_NEAR(at(0.0f, true), 0.0f, 1e-5f);
    EXPECT_NEAR(at(1.0f, true), 1.0f, 1e-5f);
    EXPECT_NEAR(at(2.0f, true), 2.0f, 1e-5f);
    EXPECT_NEAR(at(3.0f, true), 3.0f, 1e-5f);
    EXPECT_NEAR(at(8.0f, true), 4.0f, 1e-5f); // clamped to the last level
    // Between levels: the nearest (d = ceil(λ + ½) − 1), where trilinear blends.
    const float lambda = std::log2(2.8f); // llvmpipe's approximation: λ ≈ 1.4
    EXPECT_NEAR(at(lambda, true), 1.0f, 1e-5f);
    EXPECT_GT(at(lambda, false), 1.0f);
    EXPECT_LT(at(lambda, false), 2.0f);
    EXPECT_NEAR(at(std::log2(3.4f), true), 2.0f, 1e-5f); // λ ≈ 1.7
    // sampleFiltered dispatches on the filter.
    const glm::vec2 d(std::exp2(lambda) / 16.0f, 0.0f);
    EXPECT_EQ(strata::render::sampleFiltered(texture, strata::render::TextureFilter::Bilinear, {0.3f, 0.6f}, d, d),
              strata::render::sampleBilinearNearestMip(texture, {0.3f, 0.6f}, d, d));
    EXPECT_EQ(strata::render::sampleFiltered(texture, strata::render::TextureFilter::Trilinear, {0.3f, 0.6f}, d, d),
              strata::render::sampleTrilinear(texture, {0.3f, 0.6f}, d, d));
}
