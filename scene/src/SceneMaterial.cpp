// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/SceneMaterial.h>

#include "SceneReaders.h"

#include <strata/Error.h>
#include <strata/render/PbrFolder.h>
#include <strata/render/ProceduralTextures.h>

#include <initializer_list>
#include <map>

namespace strata::scene {

namespace {

constexpr render::MapKind SLOT_KINDS[9] = {
    render::MapKind::Albedo, render::MapKind::Mask,         render::MapKind::Normal,
    render::MapKind::Albedo, render::MapKind::Mask,         render::MapKind::Normal,
    render::MapKind::Detail, render::MapKind::DetailNormal, render::MapKind::Emission,
};

/// Output channels each kind of map uses (albedo RGB, mask RGBA, normal RG, detail RB, emission RGB).
bool channelUsed(render::MapKind kind, int c)
{
    switch (kind) {
    case render::MapKind::Albedo:
    case render::MapKind::Emission:
        return c < 3;
    case render::MapKind::Mask:
        return true;
    case render::MapKind::Normal:
    case render::MapKind::DetailNormal:
        return c < 2;
    case render::MapKind::Detail:
        return c == 0 || c == 2;
    }
    return true;
}

std::string setName(TableReader& t, const std::string& key, const std::string& fallback)
{
    const std::string name = t.string(key, fallback);
    if (name != "none" && !render::builtinSetFromName(name)) {
        t.fail(nullptr, key,
               "= '" + name +
                   "' is not a built-in texture set (rock, grass, soil, sand, snow, "
                   "circuitry or none)");
    }
    return name;
}

std::filesystem::path resolve(const std::filesystem::path& baseDir, const std::string& file)
{
    const std::filesystem::path p(file);
    return p.is_absolute() || baseDir.empty() ? p : baseDir / p;
}

void readMapFile(TableReader& maps, int slot, MaterialSettings& settings, const std::filesystem::path& baseDir)
{
    const std::string key = MATERIAL_MAP_KEYS[slot];
    if (!maps.has(key)) {
        maps.table(key); // marks it used
        return;
    }
    TableReader t = maps.table(key);
    MapFileSettings f;
    f.where = maps.where(key);
    const render::MapKind kind = SLOT_KINDS[slot];
    const std::string file = t.string("file", "");
    bool packed = false;
    if (kind == render::MapKind::Mask) {
        static const char* PACK[4] = {"metallic", "occlusion", "height", "smoothness"};
        for (int c = 0; c < 4; ++c) {
            const std::string packFile = t.string(PACK[c], "");
            const std::string channel = t.string(std::string(PACK[c]) + "_channel", "r");
            f.packChannels[std::size_t(c)] =
                render::parseChannelSource(channel, t.where(std::string(PACK[c]) + "_channel"));
            if (!packFile.empty()) {
                f.packFiles[std::size_t(c)] = resolve(baseDir, packFile);
                packed = true;
            }
        }
    }
    if (file.empty() && !packed) {
        t.fail(nullptr, "file", "is required (the image file of the map)");
    }
    if (!file.empty() && packed) {
        t.fail(nullptr, "file", "cannot be combined with separate metallic/occlusion/height/smoothness images");
    }
    f.file = file.empty() ? std::filesystem::path() : resolve(baseDir, file);
    if (const toml::node* node = t.node("channels")) {
        const toml::array* array = node->as_array();
        if (!array || array->size() != 4) {
            t.fail(node, "channels",
                   TableReader::shown(node) + "must be an array of four channel names, e.g. [\"r\", \"g\", \"b\", \"1-a\"]");
        }
        for (std::size_t c = 0; c < 4; ++c) {
            const auto value = array->get(c)->value<std::string>();
            if (!value) t.fail(node, "channels", TableReader::shown(node) + "must be an array of four strings");
            f.channels.channels[c] = render::parseChannelSource(*value, t.where("channels"));
        }
    }
    const std::string convention = t.string("convention", "opengl");
    if (convention != "opengl" && convention != "directx") {
        t.fail(nullptr, "convention", "= '" + convention + "' must be \"opengl\" (+Y) or \"directx\" (-Y)");
    }
    f.directX = convention == "directx";
    const bool identity = [&] {
        for (int c = 0; c < 4; ++c) {
            if (f.channels.channels[c].channel != c || f.channels.channels[c].invert) return false;
        }
        return true;
    }();
    f.minChannels = 1;
    if (!(identity && (kind == render::MapKind::Albedo || kind == render::MapKind::Emission))) {
        for (int c = 0; c < 4; ++c) {
            const int source = f.channels.channels[c].channel;
            if (channelUsed(kind, c) && source < 4) f.minChannels = std::max(f.minChannels, source + 1);
        }
    }
    t.finish(); // unknown keys first, then the files
    if (!f.file.empty()) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(f.file, ec)) {
            t.fail(nullptr, "file",
                   "= '" + f.file.string() + "': no such file (material '" + settings.name + "', map " + key + ")");
        }
    }
    for (int c = 0; c < 4; ++c) {
        std::error_code ec;
        if (!f.packFiles[std::size_t(c)].empty() &&
            !std::filesystem::is_regular_file(f.packFiles[std::size_t(c)], ec)) {
            static const char* PACK[4] = {"metallic", "occlusion", "height", "smoothness"};
            t.fail(nullptr, PACK[c],
                   "= '" + f.packFiles[std::size_t(c)].string() + "': no such file (material '" + settings.name +
                       "', map " + key + ")");
        }
    }
    settings.files[std::size_t(slot)] = f;
}

void readMaterialTable(TableReader& m, MaterialSettings& s, const std::filesystem::path& baseDir)
{
    render::Material& p = s.parameters;
    p.mapScale = float(m.number("map_scale", p.mapScale, 1e-6, 1e6));
    p.blendOffset = float(m.number("blend_offset", p.blendOffset, 0.0, 0.5));
    p.blendExponent = float(m.number("blend_exponent", p.blendExponent, 1.0, 8.0));
    p.projections = int(m.integer("projections", p.projections, 2, 3));
    p.antiTiling = m.boolean("anti_tiling", p.antiTiling);
    p.antiTilingSharpness = float(m.number("anti_tiling_sharpness", p.antiTilingSharpness, 1.0, 16.0));
    p.heightStrength = float(m.number("height_strength", p.heightStrength, 0.0, 0.99));
    s.textureSize = int(m.integer("texture_size", s.textureSize, 16, 4096));
    if ((s.textureSize & (s.textureSize - 1)) != 0) {
        m.fail(nullptr, "texture_size", "= " + std::to_string(s.textureSize) + " must be a power of two");
    }
    s.textureSeed = std::uint32_t(m.integer("texture_seed", s.textureSeed, 0, 0xffffffffll));
    if (m.has("pbr")) {
        s.pbr = resolve(baseDir, m.string("pbr", ""));
        s.pbrWhere = m.where("pbr");
        std::error_code ec;
        if (!std::filesystem::is_directory(s.pbr, ec)) {
            m.fail(nullptr, "pbr", "= '" + s.pbr.string() + "': no such folder (a PBR texture set)");
        }
    }
    s.pbrMaxSize = int(m.integer("pbr_max_size", s.pbrMaxSize, 0, render::MAX_MAP_SIZE));
    if (s.pbrMaxSize != 0 && (s.pbrMaxSize & (s.pbrMaxSize - 1)) != 0) {
        m.fail(nullptr, "pbr_max_size", "= " + std::to_string(s.pbrMaxSize) + " must be 0 (keep) or a power of two");
    }
    const std::string pbrConvention = m.string("pbr_convention", s.pbrDirectX ? "directx" : "opengl");
    if (pbrConvention != "opengl" && pbrConvention != "directx") {
        m.fail(nullptr, "pbr_convention", "= '" + pbrConvention + "' must be \"opengl\" or \"directx\"");
    }
    s.pbrDirectX = pbrConvention == "directx";
    s.side = setName(m, "side", s.side);
    s.top = setName(m, "top", s.top);
    s.detail = setName(m, "detail", s.detail);
    s.emission = setName(m, "emission", s.emission);
    s.maskMaps = m.boolean("mask_maps", s.maskMaps);
    s.normalMaps = m.boolean("normal_maps", s.normalMaps);
    s.detailNormals = m.boolean("detail_normals", s.detailNormals);
    const std::string blend = m.string("normal_blend", p.normalBlend == render::NormalBlend::Udn   ? "udn"
                                                       : p.normalBlend == render::NormalBlend::Rnm ? "rnm"
                                                                                                   : "whiteout");
    if (blend == "whiteout")
        p.normalBlend = render::NormalBlend::Whiteout;
    else if (blend == "udn")
        p.normalBlend = render::NormalBlend::Udn;
    else if (blend == "rnm")
        p.normalBlend = render::NormalBlend::Rnm;
    else
        m.fail(nullptr, "normal_blend", "= '" + blend + "' must be \"whiteout\", \"udn\" or \"rnm\"");
    const std::string layout = m.string("mask_layout", p.maskLayout == render::MaskLayout::Mods ? "mods" : "mohs");
    if (layout == "mohs")
        p.maskLayout = render::MaskLayout::Mohs;
    else if (layout == "mods")
        p.maskLayout = render::MaskLayout::Mods;
    else
        m.fail(nullptr, "mask_layout", "= '" + layout + "' must be \"mohs\" or \"mods\"");
    p.normalStrength = float(m.number("normal_strength", p.normalStrength, 0.0, 4.0));
    p.occlusionStrength = float(m.number("occlusion_strength", p.occlusionStrength, 0.0, 1.0));
    p.metallic = float(m.number("metallic", p.metallic, 0.0, 1.0));
    p.smoothness = float(m.number("smoothness", p.smoothness, 0.0, 1.0));
    p.fresnelStrength = float(m.number("fresnel_strength", p.fresnelStrength, 0.0, 1.0));
    p.detailScale = float(m.number("detail_scale", p.detailScale, 1e-3, 1e3));
    p.detailAlbedo = float(m.number("detail_albedo", p.detailAlbedo, 0.0, 1.0));
    p.detailSmoothness = float(m.number("detail_smoothness", p.detailSmoothness, 0.0, 1.0));
    p.detailNormalStrength = float(m.number("detail_normal_strength", p.detailNormalStrength, 0.0, 1.0));
    s.detailFadeStart = float(m.number("detail_fade_start", s.detailFadeStart, 0.0, 16.0));
    s.detailFadeEnd = float(m.number("detail_fade_end", s.detailFadeEnd, 0.0, 16.0));
    if (s.detailFadeEnd < s.detailFadeStart) {
        m.fail(nullptr, "detail_fade_end", m.shown("detail_fade_end") + "must be >= material.detail_fade_start (" +
                                               formatNumber(s.detailFadeStart) + ")");
    }
    auto colour = [&](const std::string& key, glm::vec3& value, double limit) {
        if (const std::optional<glm::dvec3> v = m.vec3(key, limit)) {
            for (int c = 0; c < 3; ++c) {
                if ((*v)[c] < 0.0) m.fail(nullptr, key, m.shown(key) + "must not be negative");
            }
            value = glm::vec3(*v);
        }
    };
    colour("albedo_tint", p.albedoTint, 16.0);
    colour("emission_color", p.emissionColor, 1e4);

    TableReader maps = m.table("maps");
    for (int slot = 0; slot < 9; ++slot) {
        readMapFile(maps, slot, s, baseDir);
    }
    maps.finish();
}

render::TexturePtr loadSlot(const MapFileSettings& f, render::MapKind kind, const MaterialSettings& settings,
                            const render::MipOptions& mips)
{
    const std::string what = f.where + " (material '" + settings.name + "')";
    render::Image image;
    if (!f.file.empty()) {
        image = render::loadMapImage(f.file, kind, f.minChannels, what);
        image = render::remapChannels(image, f.channels);
    } else {
        render::Image parts[4];
        const render::Image* pointers[4] = {nullptr, nullptr, nullptr, nullptr};
        for (int c = 0; c < 4; ++c) {
            if (f.packFiles[std::size_t(c)].empty()) continue;
            const render::ChannelSource source = f.packChannels[std::size_t(c)];
            render::Image loaded = render::loadMapImage(f.packFiles[std::size_t(c)], kind,
                                                        source.channel < 4 ? source.channel + 1 : 1, what);
            render::ChannelMapping mapping;
            mapping.channels[0] = source;
            parts[c] = render::remapChannels(loaded, mapping);
            pointers[c] = &parts[c];
        }
        try {
            image = render::packMohs(pointers[0], pointers[1], pointers[2], pointers[3]);
        } catch (const Error& e) {
            throw Error(e.kind(), what + ": " + e.what());
        }
    }
    if (f.directX) render::flipGreen(image);
    return render::makeTexture(image, kind, mips);
}

/// A band from KEY_min / KEY_max / KEY_softness: on when either bound is given.
render::LayerBand readBand(TableReader& t, const std::string& key, double limit, double softness)
{
    render::LayerBand band;
    const bool hasMin = t.has(key + "_min");
    const bool hasMax = t.has(key + "_max");
    band.enabled = hasMin || hasMax;
    if (hasMin) band.min = float(t.number(key + "_min", 0.0, -limit, limit));
    if (hasMax) band.max = float(t.number(key + "_max", 0.0, -limit, limit));
    band.softness = float(t.number(key + "_softness", softness, 0.0, limit));
    if (hasMin && hasMax && band.min > band.max) {
        t.fail(nullptr, key + "_max",
               t.shown(key + "_max") + "must be >= " + key + "_min (" + formatNumber(band.min) + ")");
    }
    return band;
}

/// Which mask sources the terrain tree has, for the layer bands on them.
struct MaskSources
{
    bool landform = false; ///< an `erode` node: flow, wear, deposition, water
    bool rock = false;     ///< a `beds` node: hardness, bed
};

/// Fails at the first bound of `bands` that `t` gives: their source is
/// missing (`needs` says what and how to add it).
void refuseBands(TableReader& t, std::initializer_list<const char*> bands, const std::string& needs)
{
    for (const char* band : bands) {
        for (const char* bound : {"_min", "_max"}) {
            const std::string key = std::string(band) + bound;
            if (t.has(key)) t.fail(nullptr, key, t.shown(key) + needs + ", or remove the " + band + " band");
        }
    }
}

/// The rule of a [[layer]] table. Bands on the landform masks need an
/// `erode` node in the terrain tree, bands on the rock masks a `beds` node.
render::LayerRule readLayerRule(TableReader& t, const MaskSources& sources)
{
    render::LayerRule r;
    r.altitude = readBand(t, "altitude", 1e7, 10.0);
    r.slope = readBand(t, "slope", 180.0, 5.0);
    r.cavity = readBand(t, "cavity", 1.0, 0.1);
    r.cover = readBand(t, "cover", 1.0, 0.1);
    r.flow = readBand(t, "flow", 20.0, 0.5);            // log10 of the drainage area in m²
    r.wear = readBand(t, "wear", 1e4, 1.0);             // metres
    r.deposition = readBand(t, "deposition", 1e4, 0.5); // metres
    r.water = readBand(t, "water", 1.0, 0.1);
    r.hardness = readBand(t, "hardness", 1.0, 0.1);
    r.bed = readBand(t, "bed", 1e6, 0.5); // the bed's index in the beds node's sequence
    if (!sources.landform) {
        refuseBands(t, {"flow", "wear", "deposition", "water"},
                    "needs the landform masks of erosion: add an `erode` node to the terrain tree ([terrain.nodes])");
    }
    if (!sources.rock) {
        refuseBands(t, {"hardness", "bed"},
                    "needs the rock masks of rock beds: add a `beds` node to the terrain tree ([terrain.nodes])");
    }
    if (t.has("noise_scale")) r.noiseFrequency = float(1.0 / t.number("noise_scale", 1.0, 0.01, 1e5));
    r.noiseThreshold = float(t.number("noise_threshold", r.noiseThreshold, 0.0, 1.0));
    r.noiseSoftness = float(t.number("noise_softness", r.noiseSoftness, 0.0, 1.0));
    r.noiseSeed = std::uint32_t(t.integer("noise_seed", r.noiseSeed, 0, 0xffffffffll));
    r.opacity = float(t.number("opacity", r.opacity, 0.0, 1.0));
    return r;
}

/// The [[layer]] array of tables, bottom to top.
void readLayers(TableReader& root, MaterialSettings& base, const std::map<std::string, MaterialSettings>& named,
                const std::filesystem::path& baseDir, const std::string& source, const MaskSources& sources)
{
    const toml::node* node = root.node("layer");
    if (!node) return;
    const toml::array* array = node->as_array();
    if (!array || !array->is_array_of_tables()) {
        root.fail(node, "layer", TableReader::shown(node) + "must be an array of tables ([[layer]] ... )");
    }
    if (int(array->size()) + 1 > render::MAX_MATERIAL_LAYERS) {
        root.fail(node, "layer",
                  "has " + std::to_string(array->size()) + " tables; at most " +
                      std::to_string(render::MAX_MATERIAL_LAYERS - 1) + " layers over [material]");
    }
    for (std::size_t i = 0; i < array->size(); ++i) {
        const std::string prefix = "layer[" + std::to_string(i + 1) + "]";
        TableReader t(array->get(i)->as_table(), prefix, source);
        LayerSettings layer;
        layer.where = t.where("name");
        const std::string use = t.string("use", "");
        if (!use.empty()) {
            auto found = named.find(use);
            if (found == named.end()) t.fail(nullptr, "use", "= '" + use + "': no [materials." + use + "] table");
            layer.material = found->second;
            layer.material.layers.clear();
        } else {
            layer.material.top = "none";
        }
        layer.material.name = t.string("name", use.empty() ? prefix : use);
        layer.rule = readLayerRule(t, sources);
        readMaterialTable(t, layer.material, baseDir);
        t.finish();
        base.layers.push_back(std::move(layer));
    }
}

} // namespace

void readMaterial(TableReader& root, MaterialSettings& settings, const std::filesystem::path& baseDir,
                  bool landformSource, bool rockSource)
{
    // Named materials first: every one is checked, the one `use`d applies.
    TableReader materials = root.table("materials");
    std::map<std::string, MaterialSettings> named;
    for (const std::string& name : materials.keys()) {
        TableReader t = materials.table(name);
        MaterialSettings s = settings;
        s.name = name;
        readMaterialTable(t, s, baseDir);
        t.finish();
        named.emplace(name, std::move(s));
    }
    materials.finish();

    TableReader m = root.table("material");
    const std::string use = m.string("use", "");
    if (!use.empty()) {
        auto found = named.find(use);
        if (found == named.end()) {
            m.fail(nullptr, "use", "= '" + use + "': no [materials." + use + "] table");
        }
        settings = found->second;
    } else {
        settings.name = "material";
    }
    settings.parameters.layerBlendDepth =
        float(m.number("layer_blend_depth", settings.parameters.layerBlendDepth, 1e-3, 100.0));
    readMaterialTable(m, settings, baseDir);
    m.finish();
    settings.layers.clear();
    readLayers(root, settings, named, baseDir, m.source(), {landformSource, rockSource});
}

render::Material buildMaterial(const MaterialSettings& settings)
{
    if (!settings.layers.empty()) {
        MaterialSettings base = settings;
        base.layers.clear();
        render::Material material = buildMaterial(base);
        for (const LayerSettings& layer : settings.layers) {
            material.layers.push_back({layer.material.name, buildMaterial(layer.material), layer.rule});
        }
        try {
            render::checkMaterial(material);
        } catch (const Error& e) {
            // Name the scene file and the [[layer]] table the message is about.
            std::string where;
            for (const LayerSettings& layer : settings.layers) {
                if (std::string(e.what()).find("layer '" + layer.material.name + "'") != std::string::npos) {
                    where = layer.where + ": ";
                    break;
                }
            }
            throw Error(ErrorKind::BadInput, where + e.what());
        }
        return material;
    }
    render::Material material = settings.parameters;
    render::MipOptions mips;
    mips.detailFadeStart = settings.detailFadeStart;
    mips.detailFadeEnd = settings.detailFadeEnd;
    std::map<std::string, render::TextureSetImages> sets;
    auto set = [&](const std::string& name) -> const render::TextureSetImages& {
        auto found = sets.find(name);
        if (found == sets.end()) {
            found = sets.emplace(name, render::makeBuiltinSet(*render::builtinSetFromName(name), settings.textureSize,
                                                              settings.textureSeed))
                        .first;
        }
        return found->second;
    };
    render::TexturePtr* slots[9] = {&material.albedo,    &material.mask,         &material.normal,
                                    &material.topAlbedo, &material.topMask,      &material.topNormal,
                                    &material.detail,    &material.detailNormal, &material.emission};
    if (settings.side != "none" && settings.pbr.empty()) {
        const auto& s = set(settings.side);
        material.albedo = render::makeTexture(s.albedo, render::MapKind::Albedo, mips);
        if (settings.maskMaps) material.mask = render::makeTexture(s.mohs, render::MapKind::Mask, mips);
        if (settings.normalMaps) material.normal = render::makeTexture(s.normal, render::MapKind::Normal, mips);
    }
    if (!settings.pbr.empty()) {
        try {
            const render::PbrMaps pbr = render::loadPbrFolder(settings.pbr, mips, settings.pbrMaxSize, settings.pbrDirectX);
            material.albedo = pbr.albedo;
            material.mask = pbr.mask;
            material.normal = pbr.normal;
        } catch (const Error& e) {
            throw Error(e.kind(), settings.pbrWhere + " (material '" + settings.name + "'): " + e.what());
        }
    }
    if (settings.top != "none") {
        const auto& s = set(settings.top);
        material.topAlbedo = render::makeTexture(s.albedo, render::MapKind::Albedo, mips);
        if (settings.maskMaps) material.topMask = render::makeTexture(s.mohs, render::MapKind::Mask, mips);
        if (settings.normalMaps) material.topNormal = render::makeTexture(s.normal, render::MapKind::Normal, mips);
    }
    if (settings.detail != "none") {
        const auto& s = set(settings.detail);
        material.detail = render::makeTexture(s.detail, render::MapKind::Detail, mips);
        if (settings.detailNormals) {
            material.detailNormal = render::makeTexture(s.normal, render::MapKind::DetailNormal, mips);
        }
    }
    if (settings.emission != "none") {
        material.emission = render::makeTexture(set(settings.emission).emission, render::MapKind::Emission, mips);
    }
    for (int slot = 0; slot < 9; ++slot) {
        if (settings.files[std::size_t(slot)]) {
            *slots[slot] = loadSlot(*settings.files[std::size_t(slot)], SLOT_KINDS[slot], settings, mips);
        }
    }
    return material;
}

} // namespace strata::scene
