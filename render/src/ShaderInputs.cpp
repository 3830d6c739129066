// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/ShaderInputs.h>

#include "AtmosphereSetup.h"
#include "LayerSetup.h"
#include "MaterialMaps.h"
#include "ShadingBridge.h"
#include "ShadowSetup.h"

#include <strata/render/Camera.h>

namespace strata::render {

namespace {

struct UniformList
{
    std::vector<ShaderUniform>& out;

    void f(const std::string& name, float v) { out.push_back({name, "float", {double(v)}}); }
    void i(const std::string& name, std::int32_t v) { out.push_back({name, "int", {double(v)}}); }
    void u(const std::string& name, std::uint32_t v) { out.push_back({name, "uint", {double(v)}}); }
    void v3(const std::string& name, const glm::vec3& v) { out.push_back({name, "vec3", {v.x, v.y, v.z}}); }
    void v4(const std::string& name, const glm::vec4& v) { out.push_back({name, "vec4", {v.x, v.y, v.z, v.w}}); }

    void material(const std::string& p, const shading::MaterialParams& m)
    {
        v3(p + ".albedoTint", m.albedoTint);
        f(p + ".blendOffset", m.blendOffset);
        f(p + ".blendExponent", m.blendExponent);
        f(p + ".heightStrength", m.heightStrength);
        f(p + ".metallic", m.metallic);
        f(p + ".smoothness", m.smoothness);
        f(p + ".occlusionStrength", m.occlusionStrength);
        f(p + ".normalStrength", m.normalStrength);
        f(p + ".detailScale", m.detailScale);
        f(p + ".detailAlbedo", m.detailAlbedo);
        f(p + ".detailSmoothness", m.detailSmoothness);
        f(p + ".detailNormalStrength", m.detailNormalStrength);
        f(p + ".biplanar", m.biplanar);
        f(p + ".antiTilingSharpness", m.antiTilingSharpness);
        v3(p + ".emissionColor", m.emissionColor);
        f(p + ".fresnelStrength", m.fresnelStrength);
    }

    void layer(const std::string& p, const shading::LayerParams& l)
    {
        v4(p + ".altitude", l.altitude);
        v4(p + ".slope", l.slope);
        v4(p + ".cavity", l.cavity);
        v4(p + ".cover", l.cover);
        v4(p + ".flow", l.flow);
        v4(p + ".wear", l.wear);
        v4(p + ".deposition", l.deposition);
        v4(p + ".water", l.water);
        v4(p + ".hardness", l.hardness);
        v4(p + ".bed", l.bed);
        v4(p + ".noise", l.noise);
        v4(p + ".noiseOffset", l.noiseOffset);
        v4(p + ".textureOffset", l.textureOffset);
        v4(p + ".detailOffset", l.detailOffset);
        v4(p + ".tileOffset", l.tileOffset);
        f(p + ".mapScale", l.mapScale);
        f(p + ".opacity", l.opacity);
        u(p + ".features", l.features);
        u(p + ".seed", l.seed);
    }
};

} // namespace

TerrainShaderInputs terrainShaderInputs(const Material& material, const Lighting& lighting, const glm::dvec3& origin,
                                        std::uint32_t featureMask)
{
    checkMaterial(material);
    TerrainShaderInputs r;
    r.features = effectiveFeatures(material, featureMask);
    r.layerCount = (r.features & feature::LAYERS) ? 1 + int(material.layers.size()) : 1;
    UniformList list{r.uniforms};

    // FrameBlock's material part, as GlRenderer::draw() sets it.
    const detail::TextureRebase rebase = detail::rebaseTextures(material.mapScale, material.detailScale, origin);
    list.f("uFrame.mapScale", material.mapScale);
    list.v4("uFrame.textureOffset", glm::vec4(rebase.textureOffset, 0.0f));
    list.v4("uFrame.detailOffset", glm::vec4(rebase.detailOffset, 0.0f));
    list.v4("uFrame.tileOffset", glm::vec4(rebase.tileOffset, 0.0f));

    list.material("uMaterial", detail::toShading(material));

    const shading::LightingParams l = detail::toShading(lighting);
    for (int k = 0; k < STRATA_MAX_LIGHTS; ++k) {
        const std::string p = "uLighting.lights[" + std::to_string(k) + "]";
        list.v3(p + ".direction", l.lights[k].direction);
        list.v3(p + ".color", l.lights[k].color);
    }
    list.i("uLighting.lightCount", l.lightCount);
    list.v3("uLighting.skyAmbient", l.skyAmbient);
    list.v3("uLighting.groundAmbient", l.groundAmbient);
    list.f("uLighting.exposure", l.exposure);

    if (r.features & feature::LAYERS) {
        const shading::LayerSetParams set = detail::makeLayerSet(material, origin, featureMask);
        for (int k = 0; k < STRATA_MAX_LAYERS; ++k) {
            list.layer("uLayerSet.layers[" + std::to_string(k) + "]", set.layers[k]);
            list.material("uLayerSet.materials[" + std::to_string(k) + "]", set.materials[k]);
        }
        list.i("uLayerSet.count", set.count);
        list.f("uLayerSet.blendDepth", set.blendDepth);
    }

    // The camera and viewport parts are the viewer's, per frame.
    const shading::AtmosphereParams a = detail::makeAtmosphereParams(lighting, Camera{}, origin, 1, 1);
    list.v3("uAtmosphere.zenithColor", a.zenithColor);
    list.f("uAtmosphere.fogDensity", a.fogDensity);
    list.v3("uAtmosphere.horizonColor", a.horizonColor);
    list.f("uAtmosphere.fogFalloff", a.fogFalloff);
    list.v3("uAtmosphere.sunDirection", a.sunDirection);
    list.f("uAtmosphere.fogBaseHeight", a.fogBaseHeight);
    list.v3("uAtmosphere.sunColor", a.sunColor);
    list.f("uAtmosphere.sunGlow", a.sunGlow);
    list.f("uAtmosphere.sunDiscCos", a.sunDiscCos);
    list.i("uAtmosphere.enabled", a.enabled);
    list.f("uAtmosphere.exposure", a.exposure);

    const detail::LayerMaps maps = detail::resolveLayerMaps(material);
    r.maps = maps.slots;
    return r;
}

std::vector<ShaderUniform> shadowShaderUniforms(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                                                const glm::dvec3& origin, const Lighting& lighting,
                                                const ShadowOptions& shadows)
{
    detail::MeshBounds bounds;
    bounds.lo = glm::vec3(boundsMin - origin);
    bounds.hi = glm::vec3(boundsMax - origin);
    const shading::ShadowParams sp = detail::makeShadowParams(bounds, lighting, shadows);
    std::vector<ShaderUniform> out;
    std::vector<double> matrix;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) matrix.push_back(sp.lightViewProjection[c][r]); // column-major, as GL and three.js
    out.push_back({"uShadow.lightViewProjection", "mat4", matrix});
    out.push_back({"uShadow.lightDirection", "vec3", {sp.lightDirection.x, sp.lightDirection.y, sp.lightDirection.z}});
    out.push_back({"uShadow.texelSize", "float", {sp.texelSize}});
    out.push_back({"uShadow.normalBias", "float", {sp.normalBias}});
    out.push_back({"uShadow.depthBias", "float", {sp.depthBias}});
    out.push_back({"uShadow.resolution", "int", {double(sp.resolution)}});
    out.push_back({"uShadow.enabled", "int", {double(sp.enabled)}});
    return out;
}

} // namespace strata::render
