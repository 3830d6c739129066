// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The shared GLSL/C++ shading header, compiled as C++ through its prelude.

#include "ShadingPrelude.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

namespace {

using namespace strata::shading;

/// Deterministic unit vectors (integer hash, no <random> distributions).
class NormalSource
{
public:
    vec3 next()
    {
        for (;;) {
            const vec3 v{unit() * 2.0f - 1.0f, unit() * 2.0f - 1.0f, unit() * 2.0f - 1.0f};
            const float len = glm::length(v);
            if (len > 1e-3f && len <= 1.0f) {
                return v / len;
            }
        }
    }

private:
    float unit()
    {
        mState = mState * 6364136223846793005ULL + 1442695040888963407ULL;
        return float(mState >> 40) / float(1 << 24);
    }
    std::uint64_t mState = 12345;
};

void expectValidWeights(const vec3& w, const vec3& n, float offset, float exponent)
{
    SCOPED_TRACE(::testing::Message() << "n = (" << n.x << ", " << n.y << ", " << n.z << "), offset " << offset
                                      << ", exponent " << exponent);
    for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(std::isfinite(w[i]));
        EXPECT_GE(w[i], 0.0f);
        EXPECT_LE(w[i], 1.0f);
    }
    EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-5f);
}

TEST(TriplanarShading, WeightsAreAPartitionOfUnityForRandomNormals)
{
    NormalSource normals;
    for (int i = 0; i < 2000; ++i) {
        const vec3 n = normals.next();
        for (float offset : {0.0f, 0.25f, 0.5f}) {
            for (float exponent : {1.0f, 2.0f, 4.0f, 8.0f}) {
                expectValidWeights(triplanarWeights(n, offset, exponent), n, offset, exponent);
            }
        }
    }
}

TEST(TriplanarShading, WeightsForDegenerateNormalsFallBackToTheDominantAxis)
{
    const float denormal = std::numeric_limits<float>::denorm_min();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (float offset : {0.0f, 0.5f}) {
        for (float exponent : {1.0f, 8.0f}) {
            EXPECT_EQ(triplanarWeights(vec3(0.0f), offset, exponent), vec3(1.0f, 0.0f, 0.0f));
            EXPECT_EQ(triplanarWeights(vec3(0.0f, denormal, 0.0f), offset, exponent), vec3(0.0f, 1.0f, 0.0f));
            EXPECT_EQ(triplanarWeights(vec3(0.0f, 0.0f, -denormal), offset, exponent), vec3(0.0f, 0.0f, 1.0f));
            const vec3 tiny{1e-30f, -3e-30f, 2e-30f};
            expectValidWeights(triplanarWeights(tiny, offset, exponent), tiny, offset, exponent);
            const vec3 withNan{nan, 0.5f, 0.5f};
            expectValidWeights(triplanarWeights(withNan, offset, exponent), withNan, offset, exponent);
        }
    }
    // Every component cut away by the offset: the largest still wins.
    EXPECT_EQ(triplanarWeights(vec3(0.3f, 0.4f, 0.2f), 0.5f, 4.0f), vec3(0.0f, 1.0f, 0.0f));
}

TEST(TriplanarShading, WeightsSelectTheAxisOfAnAxisAlignedNormal)
{
    for (float sign : {1.0f, -1.0f}) {
        EXPECT_EQ(triplanarWeights(vec3(sign, 0.0f, 0.0f), 0.25f, 4.0f), vec3(1.0f, 0.0f, 0.0f));
        EXPECT_EQ(triplanarWeights(vec3(0.0f, sign, 0.0f), 0.25f, 4.0f), vec3(0.0f, 1.0f, 0.0f));
        EXPECT_EQ(triplanarWeights(vec3(0.0f, 0.0f, sign), 0.25f, 4.0f), vec3(0.0f, 0.0f, 1.0f));
    }
}

TEST(TriplanarShading, WeightsMatchTheFormulaAndAreSymmetric)
{
    const vec3 n = glm::normalize(vec3(1.0f, 2.0f, -0.5f));
    for (float offset : {0.0f, 0.25f}) {
        for (float exponent : {1.0f, 4.0f}) {
            vec3 expected;
            for (int i = 0; i < 3; ++i) {
                expected[i] = std::pow(std::max(std::abs(n[i]) - offset, 0.0f), exponent);
            }
            expected /= expected.x + expected.y + expected.z;
            const vec3 w = triplanarWeights(n, offset, exponent);
            const vec3 mirrored = triplanarWeights(-n, offset, exponent);
            for (int i = 0; i < 3; ++i) {
                EXPECT_NEAR(w[i], expected[i], 1e-6f);
                EXPECT_EQ(w[i], mirrored[i]);
            }
        }
    }
    // A larger exponent or offset sharpens the blend towards the dominant axis.
    EXPECT_GT(triplanarWeights(n, 0.0f, 8.0f).y, triplanarWeights(n, 0.0f, 1.0f).y);
    EXPECT_GT(triplanarWeights(n, 0.5f, 1.0f).y, triplanarWeights(n, 0.0f, 1.0f).y);
}

TEST(TriplanarShading, UvMatchesTheDocumentedValues)
{
    const vec3 p{1.0f, 2.0f, 3.0f};
    EXPECT_EQ(triplanarUV(p, vec3(1, 0, 0)).x, vec2(-3.0f, 2.5f));
    EXPECT_EQ(triplanarUV(p, vec3(-1, 0, 0)).x, vec2(3.0f, 2.5f));
    EXPECT_EQ(triplanarUV(p, vec3(0, 1, 0)).y, vec2(-1.0f, 3.0f));
    EXPECT_EQ(triplanarUV(p, vec3(0, -1, 0)).y, vec2(1.0f, 3.0f));
    EXPECT_EQ(triplanarUV(p, vec3(0, 0, 1)).z, vec2(1.5f, 2.0f));
    EXPECT_EQ(triplanarUV(p, vec3(0, 0, -1)).z, vec2(-0.5f, 2.0f));
    // Opposite faces see U in opposite directions; V is never flipped.
    for (const vec3& n : {vec3(0.6f, 0.64f, 0.48f), vec3(-0.2f, 0.9f, -0.387f)}) {
        const TriplanarUV a = triplanarUV(p, n);
        const TriplanarUV b = triplanarUV(p, -n);
        EXPECT_EQ(a.x.x, -b.x.x);
        EXPECT_EQ(a.y.x, -b.y.x);
        EXPECT_EQ(a.z.x - 0.5f, -(b.z.x - 0.5f));
        EXPECT_EQ(a.x.y, b.x.y);
        EXPECT_EQ(a.y.y, b.y.y);
        EXPECT_EQ(a.z.y, b.z.y);
    }
}

/// Gradient of one projection's (U, V) with respect to world position.
void uvAxes(const vec3& n, int projection, vec3& axisU, vec3& axisV)
{
    const vec3 p{0.25f, 0.75f, 0.125f}; // exact in float, so the differences are too
    auto uvOf = [&](const vec3& q) {
        const TriplanarUV uv = triplanarUV(q, n);
        return projection == 0 ? uv.x : projection == 1 ? uv.y : uv.z;
    };
    const vec2 base = uvOf(p);
    for (int i = 0; i < 3; ++i) {
        vec3 q = p;
        q[i] += 1.0f;
        const vec2 d = uvOf(q) - base;
        axisU[i] = d.x;
        axisV[i] = d.y;
    }
}

TEST(TriplanarShading, NoFaceSeesItsTextureMirrored)
{
    // Seen from outside (looking along −n), a texture is unmirrored when U
    // runs to the right and V up, i.e. when axisU × axisV points along n.
    const vec3 faces[6] = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)};
    for (const vec3& n : faces) {
        const int projection = n.x != 0.0f ? 0 : n.y != 0.0f ? 1 : 2;
        vec3 axisU, axisV;
        uvAxes(n, projection, axisU, axisV);
        SCOPED_TRACE(::testing::Message() << "face (" << n.x << ", " << n.y << ", " << n.z << ")");
        EXPECT_EQ(glm::dot(axisU, n), 0.0f);
        EXPECT_EQ(glm::dot(axisV, n), 0.0f);
        EXPECT_EQ(glm::cross(axisU, axisV), n);
        if (projection != 1) {
            EXPECT_EQ(axisV, vec3(0, 1, 0)); // side faces: texture up is world up
        }
    }
}

TEST(TriplanarShading, BlendLightingAndToneMap)
{
    EXPECT_EQ(triplanarBlend(vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), vec3(0.2f, 0.3f, 0.5f)),
              vec3(0.2f, 0.3f, 0.5f));
    const vec3 albedo{0.5f};
    const vec3 up{0, 1, 0};
    // Lit from straight above: sun plus the full sky ambient.
    const vec3 lit = shadeLambertHemisphere(albedo, up, up, vec3(2.0f), vec3(0.4f), vec3(0.1f));
    EXPECT_NEAR(lit.x, 0.5f * (2.0f + 0.4f), 1e-6f);
    // Facing down, away from the sun: only the ground ambient.
    const vec3 dark = shadeLambertHemisphere(albedo, -up, up, vec3(2.0f), vec3(0.4f), vec3(0.1f));
    EXPECT_NEAR(dark.x, 0.5f * 0.1f, 1e-6f);
    const vec3 mapped = toneMapAces(vec3(0.0f, 1.0f, 100.0f));
    EXPECT_NEAR(mapped.x, 0.0f, 1e-6f);
    EXPECT_GT(mapped.y, 0.7f);
    EXPECT_LT(mapped.y, 0.9f);
    EXPECT_EQ(mapped.z, 1.0f);
}

// Biplanar mapping: the smallest normal component's projection always has
// weight zero, the weights still sum to one, and they are continuous where
// the smallest axis changes (both smallest cut there); triplanar unchanged.
TEST(Biplanar, CutsTheSmallestAxisAndStaysContinuous)
{
    NormalSource normals;
    for (int i = 0; i < 10000; ++i) {
        const vec3 n = normals.next();
        const vec3 a = glm::abs(n);
        const int minor = a.x <= a.y && a.x <= a.z ? 0 : (a.y <= a.z ? 1 : 2);
        for (const float offset : {0.0f, 0.25f, 0.5f}) {
            EXPECT_EQ(biplanarOffset(n, offset, 0.0f), offset);
            const vec3 w = triplanarWeights(n, biplanarOffset(n, offset, 1.0f), 4.0f);
            EXPECT_EQ(w[minor], 0.0f) << n.x << " " << n.y << " " << n.z;
            EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-5f);
            EXPECT_GE(biplanarOffset(n, offset, 1.0f), offset);
        }
    }
    // Across the switch of the smallest axis (x and z equal, y dominant).
    for (const float e : {1e-3f, 1e-5f}) {
        const vec3 left = glm::normalize(vec3(0.3f - e, 0.9f, 0.3f + e));
        const vec3 right = glm::normalize(vec3(0.3f + e, 0.9f, 0.3f - e));
        const vec3 wl = triplanarWeights(left, biplanarOffset(left, 0.1f, 1.0f), 4.0f);
        const vec3 wr = triplanarWeights(right, biplanarOffset(right, 0.1f, 1.0f), 4.0f);
        EXPECT_LT(glm::length(wl - wr), 100.0f * e);
    }
    // The body diagonal: everything cut, the dominant-axis fallback, no NaN.
    const vec3 d = glm::normalize(vec3(1.0f));
    const vec3 w = triplanarWeights(d, biplanarOffset(d, 0.0f, 1.0f), 4.0f);
    EXPECT_EQ(w.x + w.y + w.z, 1.0f);
}

} // namespace
