// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The golden scenes of the render tests (CpuRendererTest.cpp, RenderParityTest.cpp):
// a sphere and a cube with the circuitry material under several feature sets.

#include <strata/render/Material.h>
#include <strata/render/ProceduralTextures.h>
#include <strata/render/SnapshotOptions.h>

#include "TestMeshes.h"

#include <glm/common.hpp>

#include <string>
#include <tuple>

namespace strata::test {

using namespace strata::render;

/// The circuitry set (and grass for the top maps) at 128², built once.
inline const TextureSetImages& circuitry()
{
    static const TextureSetImages set = makeBuiltinSet(BuiltinSet::Circuitry, 128, 3);
    return set;
}

inline const TextureSetImages& grass()
{
    static const TextureSetImages set = makeBuiltinSet(BuiltinSet::Grass, 128, 3);
    return set;
}

/// The circuitry material with the maps of `features` (names as featureNames()).
inline Material circuitryMaterial(const std::string& variant)
{
    const TextureSetImages& c = circuitry();
    Material m;
    m.mapScale = 0.5f;
    m.blendOffset = 0.2f;
    m.blendExponent = 8.0f;
    m.albedo = makeTexture(c.albedo, MapKind::Albedo);
    if (variant == "albedo") return m;
    m.metallic = 1.0f;
    m.smoothness = 1.0f;
    m.mask = makeTexture(c.mohs, MapKind::Mask);
    m.heightStrength = 0.9f;
    if (variant == "mohs-height") return m;
    m.normal = makeTexture(c.normal, MapKind::Normal);
    if (variant == "normal-whiteout") return m;
    if (variant == "normal-udn") {
        m.normalBlend = NormalBlend::Udn;
        return m;
    }
    if (variant == "normal-rnm") {
        m.normalBlend = NormalBlend::Rnm;
        return m;
    }
    m.detail = makeTexture(c.detail, MapKind::Detail);
    m.detailNormal = makeTexture(c.normal, MapKind::DetailNormal);
    m.emission = makeTexture(c.emission, MapKind::Emission);
    m.emissionColor = glm::vec3(4.0f);
    if (variant == "detail-emission") return m;
    // "full": also grass top maps.
    m.topAlbedo = makeTexture(grass().albedo, MapKind::Albedo);
    m.topMask = makeTexture(grass().mohs, MapKind::Mask);
    m.topNormal = makeTexture(grass().normal, MapKind::Normal);
    return m;
}

/// The golden scenes' options: `mesh` seen from azimuth 35°, elevation 30°
/// through a 40° lens filling width × height, one sample per pixel, the sun
/// and one extra light, the circuitry material of `variant`; the CPU
/// renderer takes the log2 of its level of detail as the GL specification
/// defines it (LodLog2::Exact, the default), not llvmpipe's approximation:
/// the parity tests hold llvmpipe to the reference, not the reverse.
inline SnapshotOptions goldenOptions(const TestMesh& mesh, const std::string& variant, int width = 256,
                                     int height = 256)
{
    SnapshotOptions options;
    options.width = width;
    options.height = height;
    options.samples = 1;
    options.cpuLodLog2 = LodLog2::Exact; // the specification's path (issue 30), not llvmpipe's
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    options.camera = orbitCamera(glm::dvec3(lo), glm::dvec3(hi), 35.0, 30.0, 40.0, double(width) / double(height));
    options.material = circuitryMaterial(variant);
    options.lighting.extraLights.push_back({glm::vec3(-0.6f, 0.2f, -0.5f), glm::vec3(0.4f, 0.45f, 0.6f)});
    return options;
}

/// The golden scenes: each shape under each circuitry variant.
inline const std::string GOLDEN_SHAPES[] = {"sphere", "cube"};
inline const std::string GOLDEN_VARIANTS[] = {"albedo",     "mohs-height",     "normal-whiteout", "normal-udn",
                                              "normal-rnm", "detail-emission", "full"};

/// A gtest name for a (shape, variant) parameter: "sphere_normal_udn".
inline std::string goldenTestName(const std::tuple<std::string, std::string>& param)
{
    std::string name = std::get<0>(param) + "_" + std::get<1>(param);
    for (char& c : name) {
        if (c == '-') c = '_';
    }
    return name;
}

} // namespace strata::test
