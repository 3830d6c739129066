// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/BakeViewer.h>

#include <strata/scene/SceneMaterial.h>
#include <strata/scene/Snapshot.h>
#include <strata/meshing/MeshMetrics.h>

#include "BakeManifest.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/render/Image.h>
#include <strata/render/ShaderInputs.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace strata::scene {

namespace {

bool holdsPage(const fs::path& dir)
{
    std::error_code ec;
    return !dir.empty() && fs::is_regular_file(dir / "index.html", ec) && fs::is_regular_file(dir / "viewer.js", ec);
}

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::Io, "cannot read the viewer page's file '" + path.string() + "'", {path.string()});
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

nlohmann::json vec3Json(const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

/// One map slot's texture array as one PNG: layer i's levels stacked
/// top-down (level 0 first), each level's texel rows in the texture's order
/// (bottom row first, as GL uploads them), the rest of the image zero.
render::Image packSlot(const std::vector<render::TexturePtr>& layers)
{
    const render::Texture& first = *layers.front();
    int chainHeight = 0;
    for (const render::Texture::Level& level : first.levels) chainHeight += level.height;
    render::Image image;
    image.width = first.width();
    image.height = chainHeight * int(layers.size());
    image.pixels.assign(std::size_t(image.width) * std::size_t(image.height) * 4, 0);
    int row = 0;
    for (const render::TexturePtr& texture : layers)
        for (const render::Texture::Level& level : texture->levels) {
            for (int y = 0; y < level.height; ++y, ++row)
                std::copy_n(level.texels.data() + std::size_t(y) * std::size_t(level.width) * 4,
                            std::size_t(level.width) * 4, image.at(0, row));
        }
    return image;
}

} // namespace

fs::path findViewerPage()
{
    if (const char* dir = std::getenv("STRATA_VIEWER_DIR"); dir && *dir) {
        return holdsPage(dir) ? fs::path(dir) : fs::path();
    }
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path besideExecutable = exe.parent_path().parent_path() / "share" / "strata" / "viewer";
        if (holdsPage(besideExecutable)) return besideExecutable;
    }
#ifdef STRATA_VIEWER_INSTALL_DIR
    if (holdsPage(STRATA_VIEWER_INSTALL_DIR)) return STRATA_VIEWER_INSTALL_DIR;
#endif
#ifdef STRATA_VIEWER_BUILD_DIR
    if (holdsPage(STRATA_VIEWER_BUILD_DIR)) return STRATA_VIEWER_BUILD_DIR;
#endif
    return {};
}

bool writeBakeViewer(const fs::path& bakeDir, const Scene& scene, const fs::path& page)
{
    if (!holdsPage(page)) return false;
    const fs::path out = bakeDir / "viewer";
    fs::create_directories(out / "maps");

    // The page itself (index.html, viewer.js, licences).
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(page)) {
        if (!entry.is_regular_file()) continue;
        const fs::path relative = fs::relative(entry.path(), page);
        fs::create_directories((out / relative).parent_path());
        writeFileAtomically(out / relative, readBytes(entry.path()));
    }

    // The material as `strata render DIR` draws it: positions relative to
    // the world origin (0, 0, 0), the viewer's frame.
    const render::Material material = buildMaterial(scene.material);
    const render::TerrainShaderInputs inputs = render::terrainShaderInputs(material, scene.lighting, glm::dvec3(0.0));
    nlohmann::json json;
    json["format"] = "strata-viewer";
    json["version"] = 1;
    json["tileset"] = "../tileset.json";
    json["features"] = inputs.features;
    json["layerCount"] = inputs.layerCount;
    json["origin"] = vec3Json(glm::dvec3(0.0));
    nlohmann::json uniforms = nlohmann::json::object();
    for (const render::ShaderUniform& u : inputs.uniforms)
        uniforms[u.name] = {{"type", u.type}, {"value", u.values.size() == 1 ? nlohmann::json(u.values[0]) : nlohmann::json(u.values)}};
    json["uniforms"] = uniforms;

    nlohmann::json maps = nlohmann::json::array();
    std::vector<std::pair<std::vector<render::TexturePtr>, std::string>> written;
    for (std::size_t slot = 0; slot < inputs.maps.size(); ++slot) {
        const std::vector<render::TexturePtr>& layers = inputs.maps[slot];
        std::string file;
        for (const auto& [sources, name] : written)
            if (sources == layers) file = name;
        if (file.empty()) {
            file = "maps/slot" + std::to_string(slot) + ".png";
            render::writeImage(packSlot(layers), out / file);
            written.emplace_back(layers, file);
        }
        const render::Texture& first = *layers.front();
        nlohmann::json levels = nlohmann::json::array();
        for (const render::Texture::Level& level : first.levels) levels.push_back({level.width, level.height});
        maps.push_back({{"slot", slot}, {"file", file}, {"srgb", first.srgb}, {"layers", layers.size()}, {"levels", levels}});
    }
    json["maps"] = maps;
    json["filter"] = scene.snapshot.filtering == render::TextureFilter::Bilinear ? "bilinear" : "trilinear";
    json["anisotropy"] = scene.snapshot.anisotropy;
    json["samples"] = scene.snapshot.samples;
    json["size"] = {scene.snapshot.width, scene.snapshot.height};
    json["shadows"] = scene.snapshot.shadows.enabled;
    const glm::vec3 sky = scene.lighting.skyColor;
    json["clearColor"] = {sky.x, sky.y, sky.z};

    // The camera `strata render DIR` uses, over the baked world's bounds.
    if (const std::optional<detail::BakeManifest> manifest = detail::readManifest(bakeDir)) {
        meshing::Bounds world{glm::dvec3(std::numeric_limits<double>::max()),
                              glm::dvec3(std::numeric_limits<double>::lowest())};
        for (const auto& [index, tile] : manifest->tiles)
            for (const detail::TileLevelRecord& level : tile.levels)
                if (level.file) {
                    world.min = glm::min(world.min, level.min);
                    world.max = glm::max(world.max, level.max);
                }
        if (world.min.x <= world.max.x) {
            json["bounds"] = {{"min", vec3Json(world.min)}, {"max", vec3Json(world.max)}};
            // The sun's shadow map over the world (the GL renderer fits it
            // to the mesh it draws: the chosen levels' tiles).
            for (const render::ShaderUniform& u :
                 render::shadowShaderUniforms(world.min, world.max, glm::dvec3(0.0), scene.lighting, scene.snapshot.shadows))
                json["uniforms"][u.name] = {{"type", u.type},
                                            {"value", u.values.size() == 1 ? nlohmann::json(u.values[0]) : nlohmann::json(u.values)}};
            const render::Camera camera = snapshotCamera(scene, SnapshotRequest{}, world,
                                                         double(scene.snapshot.width) / double(scene.snapshot.height),
                                                         std::nullopt);
            json["camera"] = {{"position", vec3Json(camera.position)}, {"target", vec3Json(camera.target)},
                              {"up", vec3Json(camera.up)},             {"fov", camera.fovYDegrees},
                              {"near", camera.nearPlane},              {"far", camera.farPlane}};
        }
    }
    writeFileAtomically(out / "strata.json", json.dump(1) + "\n");
    return true;
}

} // namespace strata::scene
