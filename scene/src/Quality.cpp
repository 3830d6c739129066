// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Quality.h>

#include <strata/scene/Scene.h>
#include "SceneReaders.h"

#include <strata/Error.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace strata::scene {

namespace {

enum class KnobKind
{
    Real,
    Integer,
    Choice,
};

struct Knob
{
    std::string key;
    KnobKind kind;
    double min = 0.0, max = 0.0;
    std::vector<std::string> choices;
};

const std::vector<Knob>& knobs()
{
    static const std::vector<Knob> table = {
        {"voxel_size", KnobKind::Real, 1e-4, 1e4, {}},
        {"voxel_scale", KnobKind::Real, 0.01, 100.0, {}},
        {"half_width", KnobKind::Integer, 3, 32, {}},
        {"mesher", KnobKind::Choice, 0, 0, {"volume", "surface-nets", "dual-contouring"}},
        {"adaptivity", KnobKind::Real, 0.0, 1.0, {}},
        {"normals", KnobKind::Choice, 0, 0, {"grid", "field", "face"}},
        {"projection", KnobKind::Integer, 0, 16, {}},
        {"simplify", KnobKind::Real, 1e-3, 1.0, {}},
        {"filtering", KnobKind::Choice, 0, 0, {"bilinear", "trilinear"}},
        {"normal_blend", KnobKind::Choice, 0, 0, {"whiteout", "udn", "rnm"}},
        {"projections", KnobKind::Integer, 2, 3, {}},
        {"anti_tiling", KnobKind::Choice, 0, 0, {"off", "on"}},
        {"shadow_resolution", KnobKind::Integer, 16, 16384, {}},
        {"backend", KnobKind::Choice, 0, 0, {"auto", "gl", "cpu"}},
    };
    return table;
}

const Knob* findKnob(const std::string& key)
{
    for (const Knob& knob : knobs()) {
        if (knob.key == key) return &knob;
    }
    return nullptr;
}

std::string joinChoices(const std::vector<std::string>& choices)
{
    std::string out;
    for (std::size_t i = 0; i < choices.size(); ++i) {
        out += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
    }
    return out;
}

std::string keyList()
{
    std::string out;
    for (const Knob& knob : knobs()) out += (out.empty() ? "" : ", ") + knob.key;
    return out;
}

// The presets: the only place that says what each one means.
const std::map<std::string, QualityOverrides>& presetTable()
{
    static const std::map<std::string, QualityOverrides> table = {
        {"fast",
         {{"voxel_scale", "2"},
          {"mesher", "surface-nets"},
          {"normals", "face"},
          {"simplify", "0.5"},
          {"filtering", "bilinear"},
          {"normal_blend", "udn"},
          {"projections", "2"},
          {"anti_tiling", "off"},
          {"shadow_resolution", "1024"}}},
        {"balanced", {}},
        {"accurate",
         {{"voxel_scale", "0.5"},
          {"half_width", "4"},
          {"mesher", "volume"},
          {"adaptivity", "0"},
          {"normals", "field"},
          {"projection", "2"},
          {"filtering", "trilinear"},
          {"normal_blend", "rnm"},
          {"projections", "3"},
          {"shadow_resolution", "4096"}}},
    };
    return table;
}

void checkPreset(const std::string& name, const std::string& what)
{
    if (!presetTable().count(name)) {
        throw Error(ErrorKind::BadInput, what + " '" + name + "' is not a preset (use " + joinChoices(presetNames()) + ")");
    }
}

void checkVoxelPair(const QualityOverrides& overrides, const std::string& where)
{
    if (overrides.count("voxel_size") && overrides.count("voxel_scale")) {
        throw Error(ErrorKind::BadInput, where + "voxel_size and voxel_scale cannot both be given (voxel_size is metres, voxel_scale "
                            "multiplies the scene's [sampling] voxel_size)");
    }
}

double number(const QualityOverrides& knobs, const std::string& key) { return std::strtod(knobs.at(key).c_str(), nullptr); }

void apply(const QualityOverrides& overrides, double sceneVoxel, QualitySettings& s)
{
    for (const auto& [key, value] : overrides) {
        if (key == "voxel_size") s.voxelSize = number(overrides, key);
        else if (key == "voxel_scale") s.voxelSize = sceneVoxel * number(overrides, key);
        else if (key == "half_width") s.halfWidth = int(number(overrides, key));
        else if (key == "mesher") s.mesher = value;
        else if (key == "adaptivity") s.adaptivity = number(overrides, key);
        else if (key == "normals") s.normals = value;
        else if (key == "projection") s.projectionSteps = int(number(overrides, key));
        else if (key == "simplify") s.simplifyRatio = number(overrides, key);
        else if (key == "filtering")
            s.filtering = value == "bilinear" ? render::TextureFilter::Bilinear : render::TextureFilter::Trilinear;
        else if (key == "normal_blend")
            s.normalBlend = value == "udn"   ? render::NormalBlend::Udn
                            : value == "rnm" ? render::NormalBlend::Rnm
                                             : render::NormalBlend::Whiteout;
        else if (key == "projections") s.projections = int(number(overrides, key));
        else if (key == "anti_tiling") s.antiTiling = value == "on";
        else if (key == "shadow_resolution") s.shadowResolution = int(number(overrides, key));
        else if (key == "backend") s.backend = value;
    }
}

} // namespace

const std::vector<std::string>& presetNames()
{
    static const std::vector<std::string> names = {"fast", "balanced", "accurate"};
    return names;
}

const std::vector<std::string>& qualityKeys()
{
    static const std::vector<std::string> keys = [] {
        std::vector<std::string> out;
        for (const Knob& knob : knobs()) out.push_back(knob.key);
        return out;
    }();
    return keys;
}

const std::vector<std::string>& knobChoices(const std::string& key)
{
    const Knob* knob = findKnob(key);
    if (!knob) throw Error(ErrorKind::BadInput, "unknown quality key '" + key + "' (use " + keyList() + ")");
    return knob->choices;
}

QualityOverrides presetKnobs(const std::string& name)
{
    checkPreset(name, "preset");
    return presetTable().at(name);
}

std::string checkKnob(const std::string& key, const std::string& value)
{
    const Knob* knob = findKnob(key);
    if (!knob) throw Error(ErrorKind::BadInput, "unknown quality key '" + key + "' (use " + keyList() + ")");
    if (knob->kind == KnobKind::Choice) {
        if (std::find(knob->choices.begin(), knob->choices.end(), value) == knob->choices.end()) {
            throw Error(ErrorKind::BadInput, key + " = '" + value + "' must be " + joinChoices(knob->choices));
        }
        return value;
    }
    char* end = nullptr;
    const double x = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size()) {
        throw Error(ErrorKind::BadInput, key + " = '" + value + "' must be a number");
    }
    if (!std::isfinite(x)) throw Error(ErrorKind::BadInput, key + " = '" + value + "' must be finite");
    if (knob->kind == KnobKind::Integer && x != std::floor(x)) {
        throw Error(ErrorKind::BadInput, key + " = '" + value + "' must be an integer");
    }
    if (x < knob->min || x > knob->max) {
        throw Error(ErrorKind::BadInput, key + " = '" + value + "' is out of range [" + formatNumber(knob->min) + ", " +
                    formatNumber(knob->max) + "]");
    }
    std::ostringstream canonical;
    canonical.precision(17);
    canonical << x;
    return canonical.str();
}

void addQualityFlag(const std::string& text, QualityOverrides& overrides)
{
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos) {
        throw Error(ErrorKind::BadInput, "--quality '" + text + "' must look like KEY=VALUE, e.g. mesher=surface-nets (keys: " + keyList() +
                    ")");
    }
    const std::string key = text.substr(0, equals);
    try {
        overrides[key] = checkKnob(key, text.substr(equals + 1));
    } catch (const Error& e) {
        throw Error(e.kind(), "--quality '" + text + "': " + e.what());
    }
    checkVoxelPair(overrides, "--quality: ");
}

QualityTable readQuality(TableReader& root)
{
    QualityTable out;
    TableReader table = root.table("quality");
    if (table.has("preset")) {
        const std::string preset = table.string("preset", "balanced");
        if (!presetTable().count(preset)) {
            table.fail(nullptr, "preset", "= '" + preset + "' is not a preset (use " + joinChoices(presetNames()) + ")");
        }
        out.preset = preset;
    }
    for (const Knob& knob : knobs()) {
        if (!table.has(knob.key)) continue;
        std::string text;
        switch (knob.kind) {
        case KnobKind::Real:
            text = formatNumber(table.number(knob.key, 0.0, knob.min, knob.max));
            break;
        case KnobKind::Integer:
            text = std::to_string(table.integer(knob.key, 0, std::int64_t(knob.min), std::int64_t(knob.max)));
            break;
        case KnobKind::Choice:
            text = table.string(knob.key, "");
            break;
        }
        try {
            out.knobs[knob.key] = checkKnob(knob.key, text);
        } catch (const Error&) {
            table.fail(nullptr, knob.key, "= '" + text + "' must be " + joinChoices(knob.choices));
        }
    }
    if (out.knobs.count("voxel_size") && out.knobs.count("voxel_scale")) {
        table.fail(nullptr, "voxel_scale", "cannot be combined with quality.voxel_size");
    }
    table.finish();
    return out;
}

QualitySettings resolveQuality(const Scene& scene, const std::optional<std::string>& presetFlag,
                               const QualityOverrides& flags)
{
    QualitySettings s;
    s.voxelSize = scene.voxelSize;
    s.halfWidth = scene.halfWidth;
    s.adaptivity = scene.adaptivity;
    s.shadowResolution = scene.snapshot.shadows.resolution;
    s.normalBlend = scene.material.parameters.normalBlend;
    s.projections = scene.material.parameters.projections;
    s.antiTiling = scene.material.parameters.antiTiling;
    if (presetFlag) checkPreset(*presetFlag, "--preset");
    s.preset = presetFlag.value_or(scene.quality.preset.value_or("balanced"));
    apply(presetKnobs(s.preset), scene.voxelSize, s);
    apply(scene.quality.knobs, scene.voxelSize, s);
    checkVoxelPair(flags, "--quality: ");
    apply(flags, scene.voxelSize, s);
    return s;
}

Scene applyQuality(const Scene& scene, const QualitySettings& settings)
{
    Scene out = scene;
    out.voxelSize = settings.voxelSize;
    out.halfWidth = settings.halfWidth;
    out.adaptivity = settings.adaptivity;
    out.snapshot.shadows.resolution = settings.shadowResolution;
    out.snapshot.filtering = settings.filtering;
    // The material knobs apply to the base and to every layer.
    auto knobs = [&settings](render::Material& m) {
        m.normalBlend = settings.normalBlend;
        m.projections = settings.projections;
        m.antiTiling = settings.antiTiling;
    };
    knobs(out.material.parameters);
    for (LayerSettings& layer : out.material.layers) knobs(layer.material.parameters);
    return out;
}

const char* filteringName(render::TextureFilter filter)
{
    return filter == render::TextureFilter::Bilinear ? "bilinear" : "trilinear";
}

const char* normalBlendName(render::NormalBlend blend)
{
    return blend == render::NormalBlend::Udn ? "udn" : blend == render::NormalBlend::Rnm ? "rnm" : "whiteout";
}

std::string describeQuality(const QualitySettings& s)
{
    std::ostringstream out;
    out << "preset " << s.preset << ": voxel " << s.voxelSize << " m, band " << s.halfWidth << ", " << s.mesher;
    if (s.mesher == "volume") out << " (adaptivity " << s.adaptivity << ")";
    out << ", " << s.normals << " normals";
    if (s.projectionSteps > 0) out << ", " << s.projectionSteps << " projection steps";
    if (s.simplifyRatio < 1.0) out << ", simplify " << s.simplifyRatio;
    out << ", " << filteringName(s.filtering) << ", " << normalBlendName(s.normalBlend)
        << (s.projections == 2 ? ", biplanar" : "") << (s.antiTiling ? ", anti-tiling" : "") << ", shadows "
        << s.shadowResolution << ", backend " << s.backend;
    return out.str();
}

} // namespace strata::scene
