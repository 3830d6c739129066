// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Scenes and their parts as Python objects: read-only views of what the
// scene file said (scene/Scene.h, scene/SceneMaterial.h), so a script or the
// Blender add-on reads the same values the renderers use.

#include "Bindings.h"
#include "Progress.h"

#include <strata/scene/SceneMaterial.h>

#include <filesystem>

namespace strata::python {

namespace {

using scene::LayerSettings;
using scene::MaterialSettings;
using scene::Scene;

py::object optionalVec3(const std::optional<glm::dvec3>& v) { return v ? py::object(fromVec3(*v)) : py::none(); }
py::tuple fromFloat3(const glm::vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

py::dict bandDict(const render::LayerBand& band)
{
    py::dict d;
    d["min"] = band.min;
    d["max"] = band.max;
    d["softness"] = band.softness;
    return d;
}

/// A layer rule as a dict: every enabled band by name ({"min", "max",
/// "softness"}), the noise and the opacity. Bands that are off are absent.
py::dict ruleDict(const render::LayerRule& rule)
{
    py::dict d;
    const std::pair<const char*, const render::LayerBand*> bands[] = {
        {"altitude", &rule.altitude}, {"slope", &rule.slope}, {"cavity", &rule.cavity},
        {"cover", &rule.cover},       {"flow", &rule.flow},   {"wear", &rule.wear},
        {"deposition", &rule.deposition}, {"water", &rule.water}, {"hardness", &rule.hardness}, {"bed", &rule.bed}};
    for (const auto& [name, band] : bands) {
        if (band->enabled) d[name] = bandDict(*band);
    }
    if (rule.noiseFrequency > 0.0f) {
        py::dict noise;
        noise["scale"] = rule.noiseFrequency > 0.0f ? 1.0f / rule.noiseFrequency : 0.0f;
        noise["frequency"] = rule.noiseFrequency;
        noise["threshold"] = rule.noiseThreshold;
        noise["softness"] = rule.noiseSoftness;
        noise["seed"] = rule.noiseSeed;
        d["noise"] = noise;
    }
    d["opacity"] = rule.opacity;
    return d;
}

const char* normalBlendText(render::NormalBlend blend) { return scene::normalBlendName(blend); }

/// Level 0 of every map the material's settings build, top row first.
py::dict buildMaps(const MaterialSettings& settings)
{
    render::Material material;
    {
        py::gil_scoped_release release;
        material = scene::buildMaterial(settings);
    }
    py::dict maps;
    const std::pair<const char*, const render::TexturePtr*> slots[] = {
        {"albedo", &material.albedo},         {"mask", &material.mask},
        {"normal", &material.normal},         {"top_albedo", &material.topAlbedo},
        {"top_mask", &material.topMask},      {"top_normal", &material.topNormal},
        {"detail", &material.detail},         {"detail_normal", &material.detailNormal},
        {"emission", &material.emission}};
    for (const auto& [name, texture] : slots) {
        if (!*texture || (*texture)->levels.empty()) continue;
        const render::Texture::Level& level = (*texture)->levels[0];
        py::array_t<std::uint8_t> pixels({level.height, level.width, 4});
        auto out = pixels.mutable_unchecked<3>();
        // Texture rows run bottom to top (GL's order); images top to bottom.
        for (int y = 0; y < level.height; ++y) {
            const std::uint8_t* row = level.texels.data() + std::size_t(level.height - 1 - y) * level.width * 4;
            std::copy(row, row + std::size_t(level.width) * 4, out.mutable_data(y, 0, 0));
        }
        maps[name] = pixels;
    }
    return maps;
}

using SceneClass = py::class_<Scene, std::shared_ptr<Scene>>;

/// strata.MaterialSettings: a material as the scene file gave it.
void bindMaterialSettings(py::module_& m)
{
    py::class_<MaterialSettings, std::shared_ptr<MaterialSettings>>(
        m, "MaterialSettings",
        "A material as the scene file gave it ([material] or a [[layer]]): built-in texture sets, map files,\n"
        "the triplanar blend and surface parameters. maps() builds its textures.")
        .def_readonly("name", &MaterialSettings::name)
        .def_readonly("side", &MaterialSettings::side, "built-in set of the side (albedo, mask, normal) maps, or 'none'")
        .def_readonly("top", &MaterialSettings::top, "built-in set of the top maps (drawn where the normal points up), or 'none'")
        .def_readonly("detail", &MaterialSettings::detail)
        .def_readonly("emission", &MaterialSettings::emission)
        .def_readonly("texture_size", &MaterialSettings::textureSize)
        .def_readonly("texture_seed", &MaterialSettings::textureSeed)
        .def_readonly("mask_maps", &MaterialSettings::maskMaps)
        .def_readonly("normal_maps", &MaterialSettings::normalMaps)
        .def_property_readonly("pbr", [](const MaterialSettings& s) -> py::object {
            return s.pbr.empty() ? py::none() : py::object(py::str(s.pbr.string()));
        })
        .def_property_readonly("files", [](const MaterialSettings& s) {
            py::dict files;
            for (std::size_t i = 0; i < s.files.size(); ++i) {
                if (s.files[i]) files[scene::MATERIAL_MAP_KEYS[i]] = s.files[i]->file.string();
            }
            return files;
        }, "map slot -> image file, for the slots the scene gave a file")
        .def_property_readonly("map_scale", [](const MaterialSettings& s) { return s.parameters.mapScale; },
                               "texture repeats per metre")
        .def_property_readonly("blend_offset", [](const MaterialSettings& s) { return s.parameters.blendOffset; })
        .def_property_readonly("blend_exponent", [](const MaterialSettings& s) { return s.parameters.blendExponent; })
        .def_property_readonly("projections", [](const MaterialSettings& s) { return s.parameters.projections; })
        .def_property_readonly("height_strength", [](const MaterialSettings& s) { return s.parameters.heightStrength; })
        .def_property_readonly("albedo_tint", [](const MaterialSettings& s) { return fromFloat3(s.parameters.albedoTint); })
        .def_property_readonly("metallic", [](const MaterialSettings& s) { return s.parameters.metallic; })
        .def_property_readonly("smoothness", [](const MaterialSettings& s) { return s.parameters.smoothness; })
        .def_property_readonly("occlusion_strength", [](const MaterialSettings& s) { return s.parameters.occlusionStrength; })
        .def_property_readonly("normal_strength", [](const MaterialSettings& s) { return s.parameters.normalStrength; })
        .def_property_readonly("normal_blend", [](const MaterialSettings& s) { return normalBlendText(s.parameters.normalBlend); })
        .def_property_readonly("detail_scale", [](const MaterialSettings& s) { return s.parameters.detailScale; })
        .def_property_readonly("layer_blend_depth", [](const MaterialSettings& s) { return s.parameters.layerBlendDepth; })
        .def_property_readonly("layers", [](const MaterialSettings& s) {
            py::list layers;
            for (const LayerSettings& layer : s.layers) {
                py::dict d;
                d["name"] = layer.material.name;
                d["material"] = std::make_shared<MaterialSettings>(layer.material);
                d["rule"] = ruleDict(layer.rule);
                layers.append(d);
            }
            return layers;
        }, "[[layer]] tables, bottom to top: dicts of name, material (MaterialSettings) and rule (bands by name)")
        .def("maps", &buildMaps,
             "The material's textures as the renderers see them (built-in sets generated, files loaded):\n"
             "a dict of slot name -> (height, width, 4) uint8 array, top row first. Albedo and emission are sRGB;\n"
             "mask (MOHS: metallic, occlusion, height, smoothness) and normal maps are linear.")
        .def("__repr__", [](const MaterialSettings& s) {
            return "<strata.MaterialSettings '" + s.name + "' side='" + s.side + "' top='" + s.top + "' layers=" +
                   std::to_string(s.layers.size()) + ">";
        });
}

/// Scene's source, seed, sampling, region, input files and georeference.
void bindSceneSource(SceneClass& cls)
{
    cls.def_readonly("source", &Scene::source, "the file it was read from, or '<default scene>'")
        .def_readonly("text", &Scene::text, "the TOML text")
        .def_property_readonly("seed", [](const Scene& s) { return s.terrain.seed; })
        .def_readonly("voxel_size", &Scene::voxelSize, "metres")
        .def_readonly("half_width", &Scene::halfWidth, "narrow-band half width, voxels")
        .def_readonly("adaptivity", &Scene::adaptivity)
        .def_property_readonly("region", [](const Scene& s) { return py::make_tuple(fromVec3(s.region.min), fromVec3(s.region.max)); },
                               "((xmin, ymin, zmin), (xmax, ymax, zmax)) in metres")
        .def_property_readonly("input_files", [](const Scene& s) {
            py::list files;
            for (const auto& f : s.inputFiles) files.append(f.string());
            return files;
        })
        .def_property_readonly("georeference", [](const Scene& s) -> py::object {
            if (!s.georeference) return py::none();
            return py::make_tuple(s.georeference->latitude, s.georeference->longitude, s.georeference->height);
        }, "(latitude, longitude, height) of the scene's origin from a georeferenced DEM (dem_heightfield), or None");
}

/// Scene's camera, snapshot, lighting and quality tables, as dicts.
void bindSceneViewSettings(SceneClass& cls)
{
    cls.def_property_readonly("camera", [](const Scene& s) {
            py::dict d;
            d["azimuth"] = s.camera.azimuth;
            d["elevation"] = s.camera.elevation;
            d["zoom"] = s.camera.zoom;
            d["fov"] = s.camera.fov;
            d["position"] = optionalVec3(s.camera.position);
            d["target"] = optionalVec3(s.camera.target);
            return d;
        })
        .def_property_readonly("snapshot", [](const Scene& s) {
            py::dict d;
            d["width"] = s.snapshot.width;
            d["height"] = s.snapshot.height;
            d["samples"] = s.snapshot.samples;
            d["anisotropy"] = s.snapshot.anisotropy;
            d["shadows"] = s.snapshot.shadows.enabled;
            return d;
        })
        .def_property_readonly("lighting", [](const Scene& s) {
            py::dict d;
            d["sun_direction"] = fromFloat3(s.lighting.sunDirection);
            d["sun_color"] = fromFloat3(s.lighting.sunColor);
            d["sky_ambient"] = fromFloat3(s.lighting.skyAmbient);
            d["ground_ambient"] = fromFloat3(s.lighting.groundAmbient);
            d["sky_color"] = fromFloat3(s.lighting.skyColor);
            d["exposure"] = s.lighting.exposure;
            d["atmosphere"] = s.lighting.atmosphere.enabled;
            return d;
        })
        .def_property_readonly("quality", [](const Scene& s) {
            py::dict d;
            d["preset"] = s.quality.preset ? py::object(py::str(*s.quality.preset)) : py::none();
            d["knobs"] = s.quality.knobs;
            return d;
        }, "the scene's [quality] table: its preset (or None) and knob overrides");
}

/// Scene's material, density field and the erode/beds passes behind it.
void bindSceneTerrain(SceneClass& cls)
{
    cls.def_property_readonly("material", [](const Scene& s) { return std::make_shared<MaterialSettings>(s.material); })
        .def_property_readonly("field", [](const Scene& s) { return std::const_pointer_cast<terrain::DensityField>(s.field); },
                               "the terrain's root density field (for the scene's seed)")
        .def("field_for_seed", [](const Scene& s, std::uint64_t seed) {
            return std::const_pointer_cast<terrain::DensityField>(scene::fieldForSeed(s, seed));
        }, py::arg("seed"), "The root density field for another seed (the node tree rebuilt).")
        .def_property_readonly("has_landform", [](const Scene& s) { return s.landformMasks != nullptr; },
                               "whether the terrain has an erode node whose masks layers and debug views can read")
        .def_property_readonly("has_rock", [](const Scene& s) { return s.rockMasks != nullptr; },
                               "whether the terrain has a beds node whose rock masks (hardness, bed) layers and debug views can read")
        .def_property_readonly("landform_passes", [](const Scene& s) {
            py::list passes;
            for (const scene::LandformPass& p : s.landformPasses) {
                py::dict d;
                d["node"] = p.node;
                d["cells"] = p.cells;
                d["seconds"] = p.seconds;
                d["cached"] = p.cached;
                d["steps"] = p.steps;
                d["peak_bytes"] = p.peakBytes;
                passes.append(d);
            }
            return passes;
        });
}

/// strata.Scene: a parsed scene file, read-only.
void bindSceneClass(py::module_& m)
{
    SceneClass cls(m, "Scene",
                   "A parsed scene file: the terrain's node tree, region, sampling, material,\n"
                   "lighting and camera. Read-only; sample(), bake() and World take it.");
    bindSceneSource(cls);
    bindSceneViewSettings(cls);
    bindSceneTerrain(cls);
    cls.def("resolve_quality", [](const Scene& s, std::optional<std::string> preset, const py::object& quality) {
            const scene::QualitySettings q = scene::resolveQuality(s, preset, qualityOverrides({}, quality));
            py::dict d;
            d["preset"] = q.preset;
            d["voxel_size"] = q.voxelSize;
            d["half_width"] = q.halfWidth;
            d["mesher"] = q.mesher;
            d["adaptivity"] = q.adaptivity;
            d["normals"] = q.normals;
            d["projection"] = q.projectionSteps;
            d["simplify"] = q.simplifyRatio;
            d["filtering"] = scene::filteringName(q.filtering);
            d["normal_blend"] = scene::normalBlendName(q.normalBlend);
            d["projections"] = q.projections;
            d["anti_tiling"] = q.antiTiling;
            d["shadow_resolution"] = q.shadowResolution;
            d["backend"] = q.backend;
            d["description"] = scene::describeQuality(q);
            return d;
        }, py::arg("preset") = py::none(), py::arg("quality") = py::none(),
           "The effective quality settings for a preset ('fast', 'balanced', 'accurate') and knob overrides,\n"
           "as `strata generate --preset P --quality KEY=VALUE` would use them.")
        .def("__repr__", [](const Scene& s) {
            return "<strata.Scene '" + s.source + "' seed=" + std::to_string(s.terrain.seed) +
                   " voxel_size=" + std::to_string(s.voxelSize) + ">";
        });
}

/// default_scene, default_scene_text, load_scene and parse_scene.
void bindSceneLoading(py::module_& m)
{
    m.def("default_scene", [] { return std::make_shared<Scene>(scene::defaultScene()); },
          "The scene built into Strata (the one `strata generate` uses without a scene file).");
    m.def("default_scene_text", [] { return std::string(scene::defaultSceneText()); }, "The default scene's TOML text.");
    m.def("load_scene", [](const std::filesystem::path& path, std::uint64_t maxMemory, const py::object& progressCallback) {
        scene::SceneLoadOptions options;
        options.maxMemoryBytes = maxMemory;
        PythonProgress progress(progressCallback);
        options.progress = std::ref(progress);
        // An erode node's pass may run for minutes: without the GIL, Ctrl-C
        // (KeyboardInterrupt) and progress checked at each of its steps.
        return progress.run([&] { return std::make_shared<Scene>(scene::loadScene(path, options)); });
    }, py::arg("path"), py::arg("max_memory") = 0, py::arg("progress") = py::none(),
          "Reads and parses a scene file (TOML). Raises BadInputError naming the file, line and key.\n"
          "max_memory: bytes an erode node's pass may use (0: no limit).\n"
          "progress: None or a callable taking the erode passes' progress in [0, 1]; returning False or Ctrl-C\n"
          "stops the load (KeyboardInterrupt).");
    m.def("parse_scene", [](const std::string& text, const std::string& source, std::uint64_t maxMemory,
                            const py::object& progressCallback) {
        scene::SceneLoadOptions options;
        options.maxMemoryBytes = maxMemory;
        PythonProgress progress(progressCallback);
        options.progress = std::ref(progress);
        return progress.run([&] { return std::make_shared<Scene>(scene::parseScene(text, source, options)); });
    }, py::arg("text"), py::arg("source") = "<string>", py::arg("max_memory") = 0, py::arg("progress") = py::none(),
          "Parses scene text (TOML); `source` names it in errors. Relative paths resolve against the working folder.\n"
          "progress: as for load_scene.");
}

} // namespace

void bindScene(py::module_& m)
{
    bindMaterialSettings(m);
    bindSceneClass(m);
    bindSceneLoading(m);
}

} // namespace strata::python
