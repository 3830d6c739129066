// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Quality presets and knobs: one place that says what `fast`, `balanced`
/// and `accurate` mean, and how a preset, the scene's [quality] table and
/// the `--preset` / `--quality KEY=VALUE` flags combine.
///
/// Precedence, highest first: a `--quality KEY=VALUE` flag (and `--backend`),
/// a key of the scene's [quality] table, the preset (`--preset`, else
/// [quality] preset, else `balanced`), the scene's other tables ([sampling],
/// [mesh], [snapshot], [material]) and the built-in defaults. `balanced`
/// sets nothing: it is exactly the scene as written.

#include <strata/render/Material.h>
#include <strata/render/Texture.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene {

struct Scene;

/// Knob key → value text (already checked by checkKnob(); numbers as text).
using QualityOverrides = std::map<std::string, std::string>;

/// The scene file's [quality] table.
struct QualityTable
{
    std::optional<std::string> preset; ///< [quality] preset, checked
    QualityOverrides knobs;            ///< the other keys, checked
};

/// The effective settings of one run (report.json "quality").
struct QualitySettings
{
    std::string preset = "balanced";
    double voxelSize = 0.5;         ///< metres
    int halfWidth = 3;              ///< narrow band half width, voxels
    std::string mesher = "volume";  ///< volume | surface-nets | dual-contouring
    double adaptivity = 0.0;        ///< volume mesher only, 0..1
    std::string normals = "grid";   ///< grid | field (the density field's gradient) | face
    int projectionSteps = 0;        ///< Newton steps of vertices onto the surface, 0..16
    double simplifyRatio = 1.0;     ///< target triangle fraction, (0, 1]; 1 = off
    render::TextureFilter filtering = render::TextureFilter::Trilinear;
    render::NormalBlend normalBlend = render::NormalBlend::Whiteout;
    int projections = 3;            ///< 3 triplanar, 2 biplanar (Material::projections)
    bool antiTiling = false;        ///< stochastic tiling of the base maps (Material::antiTiling)
    int shadowResolution = 2048;    ///< shadow-map texels per side
    std::string backend = "auto";   ///< auto | gl | cpu
};

/// "fast", "balanced", "accurate".
const std::vector<std::string>& presetNames();

/// The knob keys, in documentation order: voxel_size, voxel_scale,
/// half_width, mesher, adaptivity, normals, projection, simplify,
/// filtering, normal_blend, projections, anti_tiling, shadow_resolution, backend.
const std::vector<std::string>& qualityKeys();

/// The choices of a string knob (empty for numeric knobs). Throws
/// strata::Error for an unknown key.
const std::vector<std::string>& knobChoices(const std::string& key);

/// What a preset sets (balanced: nothing). Throws strata::Error "unknown
/// preset 'NAME' (use fast, balanced or accurate)".
QualityOverrides presetKnobs(const std::string& name);

/// Checks `value` (text) for knob `key` and returns it canonical (numbers
/// re-formatted). Throws strata::Error "KEY = VALUE ..." for an unknown
/// key, a value that is not a finite number in range, or not one of the
/// choices.
std::string checkKnob(const std::string& key, const std::string& value);

/// "KEY=VALUE" (a --quality flag) added to `overrides`; throws
/// strata::Error "--quality 'TEXT': ..." naming the key and value. Giving
/// both voxel_size and voxel_scale is an error.
void addQualityFlag(const std::string& text, QualityOverrides& overrides);

/// The effective settings: the scene's own values, then the preset
/// (`presetFlag`, else the scene's [quality] preset, else balanced), then
/// the [quality] keys, then `flags`. Throws strata::Error for an unknown
/// preset.
QualitySettings resolveQuality(const Scene& scene, const std::optional<std::string>& presetFlag,
                               const QualityOverrides& flags);

/// The scene with the settings that live in it applied: voxel size, half
/// width, adaptivity, shadow resolution and normal blend.
Scene applyQuality(const Scene& scene, const QualitySettings& settings);

/// "bilinear" / "trilinear"; "whiteout" / "udn" / "rnm".
const char* filteringName(render::TextureFilter filter);
const char* normalBlendName(render::NormalBlend blend);

/// One line: "preset P: voxel 0.5 m, band 3, volume (adaptivity 0), grid
/// normals, ..." for the terminal.
std::string describeQuality(const QualitySettings& settings);

} // namespace strata::scene
