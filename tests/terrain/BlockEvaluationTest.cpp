// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Block evaluation (DensityField::densities, FractalNoise::evaluate) against
// the scalar reference, bit for bit: every noise basis and fractal, every
// node type of the registry with its default keys, on voxel blocks at the
// extremes (1e9 m from the origin, voxels of 1 µm and 1 km, empty blocks,
// blocks straddling the band) and on scattered points.

#include "DefaultSceneTree.h"
#include "NoiseHash.h" // internal: noise3/noise2, seedHash
#include "NoiseKernels.h" // internal: the scalar value cells
#include "NoiseSimd.h"    // internal: hashedLanes

#include <strata/Error.h>
#include <strata/terrain/DemHeightfield.h>
#include <strata/terrain/DifferentialErosion.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/NodeRegistry.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/SimdTarget.h>
#include <strata/terrain/TalusHeightfield.h>
#include <strata/terrain/TerrainField.h>

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

/// A block of points as the sampler makes them: n³ voxels at `origin`
/// spaced `step` apart (x outer, z inner), or scattered when `scatter`.
struct Block
{
    std::vector<double> x, y, z;

    PointBlock view() const
    {
        PointBlock b{x.data(), y.data(), z.data(), x.size(), {}};
        b.box = spannedBox(b);
        return b;
    }
};

Block voxels(const glm::dvec3& origin, double step, int n)
{
    Block b;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                b.x.push_back(origin.x + i * step);
                b.y.push_back(origin.y + j * step);
                b.z.push_back(origin.z + k * step);
            }
    return b;
}

Block scattered(const glm::dvec3& centre, double spread, int count, std::uint64_t state)
{
    Block b;
    const auto next = [&state] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(state >> 11) * 0x1.0p-53 - 0.5;
    };
    for (int i = 0; i < count; ++i) {
        b.x.push_back(centre.x + spread * next());
        b.y.push_back(centre.y + spread * next());
        b.z.push_back(centre.z + spread * next());
    }
    return b;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// The blocks every field is checked on.
std::vector<std::pair<std::string, Block>> testBlocks()
{
    return {
        {"8^3 of 0.5 m at the origin", voxels({-2.0, -2.0, -2.0}, 0.5, 8)},
        {"8^3 of 0.5 m on the ground", voxels({31.0, -6.0, -17.5}, 0.5, 8)},
        {"4^3 of 2 m", voxels({100.0, 0.0, 40.0}, 2.0, 4)},
        {"2^3 of 1 um", voxels({3.0, 0.25, 7.0}, 1e-6, 2)},
        {"8^3 of 1 km", voxels({-4000.0, -4000.0, -4000.0}, 1000.0, 8)},
        {"8^3 of 0.25 m 1e9 m out", voxels({1e9, -3.0, -1e9}, 0.25, 8)},
        {"one point", voxels({0.3, 0.7, -0.2}, 1.0, 1)},
        {"empty", Block{}},
        {"scattered", scattered({0.0, 0.0, 0.0}, 200.0, 300, 7)},
        // Past 2^52 every double is an integer (a zero fraction); past 2^62
        // the lattice index saturates.
        {"2^3 beyond 2^52 and 2^62", voxels({4.6e15, 1e19, -1e300}, 1e6, 2)},
    };
}

/// 8³ voxels of 0.25 m around a point where the field changes sign (found
/// by scanning columns), so the block straddles the surface and every CSG
/// child and cave matters there; none when the field has no surface nearby.
std::vector<std::pair<std::string, Block>> surfaceBlocks(const DensityField& field)
{
    std::vector<std::pair<std::string, Block>> out;
    for (double x = -60.0; x <= 60.0 && out.size() < 3; x += 13.0)
        for (double z = -60.0; z <= 60.0 && out.size() < 3; z += 17.0)
            for (double y = -80.0; y < 80.0; y += 0.5)
                if ((field.density({x, y, z}) < 0.0) != (field.density({x, y + 0.5, z}) < 0.0)) {
                    out.emplace_back("8^3 of 0.25 m on the surface at " + std::to_string(x) + ", " + std::to_string(y) +
                                         ", " + std::to_string(z),
                                     voxels({x - 1.0, y - 1.0, z - 1.0}, 0.25, 8));
                    break;
                }
    return out;
}

void expectSameAsScalar(const DensityField& field, const std::string& name, bool needSurface = true)
{
    auto blocks = testBlocks();
    const auto surface = surfaceBlocks(field);
    if (needSurface) {
        EXPECT_FALSE(surface.empty()) << name << ": no surface found to test on";
    }
    blocks.insert(blocks.end(), surface.begin(), surface.end());
    for (const auto& [label, block] : blocks) {
        const PointBlock view = block.view();
        std::vector<double> out(view.count + 1, 12345.0);
        field.densities(view, out.data());
        EXPECT_EQ(out[view.count], 12345.0) << name << ", " << label << ": wrote past the block";
        int mismatches = 0;
        for (std::size_t i = 0; i < view.count && mismatches < 3; ++i) {
            const double scalar = field.density({view.x[i], view.y[i], view.z[i]});
            if (!sameBits(out[i], scalar)) {
                ++mismatches;
                ADD_FAILURE() << name << ", " << label << ", point " << i << " (" << view.x[i] << ", " << view.y[i]
                              << ", " << view.z[i] << "): block " << out[i] << ", scalar " << scalar;
            }
        }
    }
}

/// The float Fbm (TerrainField's noise), block against scalar.
void expectFbmSameAsScalar(const std::string& target)
{
    const Fbm fbm(42, FbmOptions{6, 2.0, 0.45});
    for (const auto& [label, block] : testBlocks()) {
        const std::size_t n = block.x.size();
        std::vector<float> out3(n), out2(n);
        fbm.evaluate(block.x.data(), block.y.data(), block.z.data(), n, out3.data());
        fbm.evaluate(block.x.data(), block.z.data(), n, out2.data());
        for (std::size_t i = 0; i < n; ++i) {
            const float s3 = fbm({block.x[i], block.y[i], block.z[i]}), s2 = fbm(glm::dvec2(block.x[i], block.z[i]));
            ASSERT_EQ(std::memcmp(&out3[i], &s3, sizeof s3), 0) << target << ": Fbm 3D, " << label << ", point " << i;
            ASSERT_EQ(std::memcmp(&out2[i], &s2, sizeof s2), 0) << target << ": Fbm 2D, " << label << ", point " << i;
        }
    }
}

/// Every basis and fractal sum, 3D and 2D, block against scalar.
void expectNoiseSameAsScalar(const std::string& target)
{
    const NoiseType noises[] = {NoiseType::GRADIENT, NoiseType::SIMPLEX, NoiseType::VALUE, NoiseType::CELLULAR_F1,
                                NoiseType::CELLULAR_F2};
    const FractalType fractals[] = {FractalType::FBM, FractalType::RIDGED, FractalType::BILLOW};
    for (const NoiseType noise : noises)
        for (const FractalType fractal : fractals) {
            const FractalNoise f(99, {noise, fractal, 4, 2.0, 0.5});
            if (noise == NoiseType::GRADIENT && fractal == FractalType::FBM) expectFbmSameAsScalar(target);
            for (const auto& [label, block] : testBlocks()) {
                const std::size_t n = block.x.size();
                std::vector<double> out3(n), out2(n);
                f.evaluate(block.x.data(), block.y.data(), block.z.data(), n, out3.data());
                f.evaluate(block.x.data(), block.z.data(), n, out2.data());
                for (std::size_t i = 0; i < n; ++i) {
                    const double s3 = f({block.x[i], block.y[i], block.z[i]});
                    const double s2 = f(glm::dvec2(block.x[i], block.z[i]));
                    ASSERT_TRUE(sameBits(out3[i], s3)) << target << ": noise " << int(noise) << " fractal " << int(fractal) << ", "
                                                       << label << ", point " << i << ": " << out3[i] << " vs " << s3;
                    ASSERT_TRUE(sameBits(out2[i], s2)) << target << ": 2D noise " << int(noise) << " fractal " << int(fractal)
                                                       << ", " << label << ", point " << i;
                }
            }
        }
}

} // namespace

TEST(BlockEvaluation, EveryNoiseAndFractalGivesTheScalarBits) { expectNoiseSameAsScalar(simdTarget()); }

TEST(BlockEvaluation, EverySimdTargetGivesTheScalarBits)
{
    // Each instruction set this machine can run, forced in turn: the block
    // path's lanes must give the scalar path's bits on all of them.
    const std::vector<std::string> targets = availableSimdTargets();
    ASSERT_FALSE(targets.empty());
    EXPECT_TRUE(targets.back() == "SCALAR" || targets.back() == "EMU128")
        << targets.back() << ": the portable fallback is always there (EMU128 where the compiler supports it)";
    for (const std::string& target : targets) {
        useSimdTarget(target);
        ASSERT_EQ(simdTarget(), target);
        expectNoiseSameAsScalar(target);
        expectSameAsScalar(*strata::test::defaultSceneTree(true), target + ": default scene (terraced)");
        expectSameAsScalar(TerrainField(TerrainOptions{}), target + ": terrain field with caves");
        TerrainOptions version2;
        version2.noiseVersion = 2;
        expectSameAsScalar(TerrainField(version2), target + ": terrain field with caves, noise version 2");
    }
    useSimdTarget("");
    EXPECT_EQ(simdTarget(), targets.front());
    try {
        useSimdTarget("NEON9000");
        ADD_FAILURE() << "an unknown target was accepted";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
        EXPECT_EQ(e.place().value, "NEON9000");
        EXPECT_NE(std::string(e.what()).find(targets.front()), std::string::npos) << e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not a strata::Error: " << e.what();
    }
}

// Choosing Strata's target leaves Highway's process-wide choice alone: other
// Highway code in the process still sees every target the CPU has (the old
// hwy::SetSupportedTargetsForTest narrowed it for everyone).
TEST(BlockEvaluation, ChoosingATargetLeavesHighwaysOwnChoiceAlone)
{
    const std::int64_t before = hwy::SupportedTargets();
    for (const std::string& target : availableSimdTargets()) {
        useSimdTarget(target);
        EXPECT_EQ(simdTarget(), target);
        EXPECT_EQ(hwy::SupportedTargets(), before) << "after choosing " << target;
    }
    useSimdTarget("");
    EXPECT_EQ(hwy::SupportedTargets(), before);
}

TEST(BlockEvaluation, EveryLaneHashedBasisGivesTheScalarBitsOnEveryTarget)
{
    // The library hashes cells in lanes only on AVX-512 (native 64-bit
    // multiplies); the kernel exists for every target and must agree on all.
    using namespace strata::terrain::detail;
    const std::uint64_t seed = seedHash(77);
    const auto scalarValue = [seed](bool threeD, double x, double y, double z) {
        if (threeD) {
            const Split3 q = splitCube({x, y, z});
            ValueCell3 cell;
            valueCell(seed, q, cell);
            return valueInCell(cell, q);
        }
        const Split2 q = splitSquare({x, y});
        ValueCell2 cell;
        valueCell(seed, q, cell);
        return valueInCell(cell, q);
    };
    const auto scalarSimplex = [seed](bool threeD, double x, double y, double z) {
        if (threeD) {
            const Split3 q = splitSimplex(glm::dvec3(x, y, z));
            GradientCell3 cell;
            simplexCell(seed, q, cell);
            return simplexInCell(cell, q);
        }
        const Split2 q = splitSimplex(glm::dvec2(x, y));
        GradientCell2 cell;
        simplexCell(seed, q, cell);
        return simplexInCell(cell, q);
    };
    for (const std::string& target : availableSimdTargets()) {
        useSimdTarget(target);
        for (const auto& [label, block] : testBlocks()) {
            const std::size_t n = block.x.size();
            for (const LaneBasis basis : {LaneBasis::GRADIENT, LaneBasis::VALUE, LaneBasis::SIMPLEX,
                                          LaneBasis::CELLULAR_F1, LaneBasis::CELLULAR_F2})
                for (const bool threeD : {true, false}) {
                    std::vector<double> cells(3 * n), fractions(3 * n), out(n);
                    const SplitPoints split{cells.data(), cells.data() + n, cells.data() + 2 * n,
                                            fractions.data(), fractions.data() + n, fractions.data() + 2 * n};
                    splitPoints(basis == LaneBasis::SIMPLEX ? Lattice::SIMPLEX : Lattice::CUBE, block.x.data(),
                                block.y.data(), threeD ? block.z.data() : nullptr, n, split);
                    hashedLanes(basis, seed, split, n, threeD, out.data());
                    for (std::size_t i = 0; i < n; ++i) {
                        const glm::dvec3 q(block.x[i], block.y[i], block.z[i]);
                        const CellularDistances cell =
                            threeD ? cellularNoise(77, q) : cellularNoise(77, glm::dvec2(q.x, q.y)); // hashes 77 to seed
                        const double scalar = basis == LaneBasis::VALUE         ? scalarValue(threeD, q.x, q.y, q.z)
                                              : basis == LaneBasis::SIMPLEX     ? scalarSimplex(threeD, q.x, q.y, q.z)
                                              : basis == LaneBasis::CELLULAR_F1 ? 2.0 * cell.f1 - 1.0
                                              : basis == LaneBasis::CELLULAR_F2 ? 2.0 * cell.f2 - 1.4
                                              : threeD                          ? noise3(seed, q)
                                                                                : noise2(seed, {q.x, q.y});
                        ASSERT_TRUE(sameBits(out[i], scalar))
                            << target << ", basis " << int(basis) << ", "
                            << (threeD ? "3D" : "2D") << ", " << label << ", point " << i << ": " << out[i] << " vs "
                            << scalar;
                    }
                }
        }
    }
    useSimdTarget("");
}

TEST(BlockEvaluation, CellsHashedInLanesHoldTheScalarCellsOnEveryTarget)
{
    // The library hashes runs' cells in lanes only on AVX-512; the kernel
    // exists for every target and must give NoiseKernels.h's cells on all,
    // far from the origin and past the 2^62 saturation too.
    using namespace strata::terrain::detail;
    const std::uint64_t seed = seedHash(91);
    const std::vector<double> floors = {0.0, -1.0, 7.0, -123456.0, 3.0e9, -4.5e15, 1.0e19, -1.0e300, 42.0, -17.0, 5.0};
    const std::size_t n = floors.size();
    std::vector<double> fx(floors), fy(n), fz(n);
    for (std::size_t r = 0; r < n; ++r) {
        fy[r] = floors[(r + 3) % n];
        fz[r] = floors[(r + 7) % n];
    }
    for (const std::string& target : availableSimdTargets()) {
        useSimdTarget(target);
        for (const InCell kind : {InCell::GRADIENT3, InCell::SIMPLEX3, InCell::VALUE3, InCell::GRADIENT2,
                                  InCell::SIMPLEX2, InCell::VALUE2}) {
            const bool threeD = kind == InCell::GRADIENT3 || kind == InCell::SIMPLEX3 || kind == InCell::VALUE3;
            const std::size_t size = cellSize(kind);
            std::vector<double> lanes(n * size);
            cellDataLanes(kind, seed, fx.data(), fy.data(), threeD ? fz.data() : nullptr, n, lanes.data());
            for (std::size_t r = 0; r < n; ++r) {
                std::vector<double> scalar;
                if (threeD) {
                    const Split3 q{latticeIndex(fx[r]), latticeIndex(fy[r]), latticeIndex(fz[r]), 0, 0, 0};
                    if (kind == InCell::VALUE3) {
                        ValueCell3 c;
                        valueCell(seed, q, c);
                        scalar.assign(c.v, c.v + 8);
                    } else {
                        GradientCell3 c;
                        if (kind == InCell::GRADIENT3) gradientCell(seed, q, c);
                        else simplexCell(seed, q, c);
                        for (const auto& g : c.g) scalar.insert(scalar.end(), {g[0], g[1], g[2]});
                    }
                } else {
                    const Split2 q{latticeIndex(fx[r]), latticeIndex(fy[r]), 0, 0};
                    if (kind == InCell::VALUE2) {
                        ValueCell2 c;
                        valueCell(seed, q, c);
                        scalar.assign(c.v, c.v + 4);
                    } else {
                        GradientCell2 c;
                        if (kind == InCell::GRADIENT2) gradientCell(seed, q, c);
                        else simplexCell(seed, q, c);
                        for (const auto& g : c.g) scalar.insert(scalar.end(), {g[0], g[1]});
                    }
                }
                ASSERT_EQ(scalar.size(), size);
                for (std::size_t k = 0; k < size; ++k)
                    ASSERT_TRUE(sameBits(lanes[r * size + k], scalar[k]))
                        << target << ", kind " << int(kind) << ", cell " << r << ", value " << k;
            }
        }
    }
    useSimdTarget("");
}

TEST(BlockEvaluation, EveryNodeTypeGivesTheScalarBits)
{
    // Children: a heightfield (block path: columns) and a sphere (default path).
    const DensityFieldPtr hills = std::make_shared<NoiseHeightfield>(5, NoiseHeightfieldOptions{});
    const DensityFieldPtr ball = std::make_shared<SphereField>(glm::dvec3(30.0, -4.0, -15.0), 6.0);
    auto image = std::make_shared<HeightImage>();
    image->width = 5;
    image->height = 4;
    for (int i = 0; i < 20; ++i) image->values.push_back(float(i % 7) / 7.0f);
    auto dem = std::make_shared<ElevationRaster>();
    dem->heights = *image;
    dem->cellStep = {30.0, -30.0};

    TalusOptions smallTalus;
    smallTalus.maxHeight = 4.0;
    smallTalus.blockCells = 16;
    int built = 0;
    for (const NodeType* type : NodeRegistry::builtin().types()) {
        NodeArgs args(type->name, 1234);
        // Height-graph nodes take height nodes only: hills, not the ball.
        const bool heightGraph = type->name.rfind("height_", 0) == 0 || type->name.rfind("mask_", 0) == 0 ||
                                 type->name.rfind("erode", 0) == 0;
        const DensityFieldPtr second = heightGraph ? hills : ball;
        for (const NodeKey& key : type->keys) {
            switch (key.type) {
            case NodeKeyType::Child:
                // scree lays a talus node's cones over its child.
                if (type->name == "scree" && key.name == "talus") {
                    args.set(key.name, DensityFieldPtr(std::make_shared<TalusHeightfield>(
                                          std::dynamic_pointer_cast<const HeightfieldBase>(hills), smallTalus)));
                } else if (type->name == "crests" && key.name == "beds") { // crests reads a beds node's rock
                    args.set(key.name, DensityFieldPtr(std::make_shared<DifferentialErosionField>(
                                          hills, std::make_shared<Lithology>(3, LithologyOptions{}),
                                          DifferentialErosionOptions{})));
                } else {
                    args.set(key.name, hills);
                }
                break;
            case NodeKeyType::Children: args.set(key.name, std::vector<DensityFieldPtr>{hills, second, hills}); break;
            case NodeKeyType::Image: args.set(key.name, std::shared_ptr<const HeightImage>(image)); break;
            case NodeKeyType::Elevation: args.set(key.name, std::shared_ptr<const ElevationRaster>(dem)); break;
            case NodeKeyType::Seed: break;
            default:
                // A talus block reads a window 12 reaches wider than itself:
                // small ones keep the test's scattered blocks cheap.
                if (type->name == "talus" && key.name == "max_height") args.set(key.name, smallTalus.maxHeight);
                else if (type->name == "talus" && key.name == "block") args.set(key.name, std::int64_t(smallTalus.blockCells));
                else if (!std::holds_alternative<std::monostate>(key.defaultValue)) args.set(key.name, key.defaultValue);
                else if (key.type == NodeKeyType::Number) args.set(key.name, key.min + 0.25 * (key.max - key.min));
                break;
            }
        }
        const DensityFieldPtr field = type->build(args);
        ASSERT_TRUE(field) << type->name;
        expectSameAsScalar(*field, type->name, false);
        ++built;
    }
    EXPECT_GE(built, 10);
}

TEST(BlockEvaluation, SmoothCsgAndTheDefaultSceneGiveTheScalarBits)
{
    expectSameAsScalar(*strata::test::defaultSceneTree(true), "default scene (terraced)");
    expectSameAsScalar(*strata::test::defaultSceneTree(false), "default scene");
    TerrainOptions terrain;
    expectSameAsScalar(TerrainField(terrain), "terrain field with caves");
    terrain.caves.enabled = false;
    expectSameAsScalar(TerrainField(terrain), "terrain field without caves");
    terrain.noiseVersion = 2;
    expectSameAsScalar(TerrainField(terrain), "terrain field without caves, noise version 2");
    terrain.caves.enabled = true;
    expectSameAsScalar(TerrainField(terrain), "terrain field with caves, noise version 2");
    const DensityFieldPtr hills = std::make_shared<NoiseHeightfield>(5, NoiseHeightfieldOptions{});
    const DensityFieldPtr ball = std::make_shared<SphereField>(glm::dvec3(-8.0, -2.0, -9.0), 12.0);
    for (const CsgOperation op : {CsgOperation::UNION, CsgOperation::SUBTRACT, CsgOperation::INTERSECT})
        for (const double smooth : {0.0, 0.5, 8.0})
            expectSameAsScalar(CsgField(op, {hills, ball}, smooth), "csg " + std::to_string(int(op)) + " smooth " +
                                                                      std::to_string(smooth));
}
