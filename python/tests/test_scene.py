# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

import pytest

import strata


def test_default_scene_parts():
    scene = strata.default_scene()
    assert scene.source == "<default scene>"
    assert scene.text == strata.default_scene_text()
    assert isinstance(scene.seed, int)
    (lo, hi) = scene.region
    assert all(a < b for a, b in zip(lo, hi))
    assert scene.voxel_size > 0
    assert scene.snapshot["width"] > 0 and scene.snapshot["height"] > 0
    assert set(scene.camera) >= {"azimuth", "elevation", "fov", "position", "target"}
    assert len(scene.lighting["sun_direction"]) == 3
    material = scene.material
    assert material.side == "rock" and material.top == "grass"
    assert 0.0 < material.blend_offset <= 0.5 and material.blend_exponent >= 1.0
    assert material.projections in (2, 3)


def test_material_maps_are_images_the_renderer_uses():
    maps = strata.default_scene().material.maps()
    assert {"albedo", "mask", "normal", "top_albedo"} <= set(maps)
    for name, pixels in maps.items():
        assert pixels.ndim == 3 and pixels.shape[2] == 4 and pixels.dtype.name == "uint8", name
        assert pixels.std() > 0, f"{name} is flat"
    # Normal maps point out of the surface: blue (z) above 0.5 on average.
    assert maps["normal"][..., 2].mean() > 160


def test_layers_and_rules(tmp_path):
    path = tmp_path / "layers.toml"
    path.write_text(strata.default_scene_text() + """
[[layer]]
side = "sand"
altitude_max = 2.0
altitude_softness = 1.0
slope_max = 30.0
""")
    scene = strata.load_scene(path)
    (layer,) = scene.material.layers
    assert layer["material"].side == "sand"
    assert layer["rule"]["altitude"]["max"] == 2.0
    assert layer["rule"]["slope"]["max"] == 30.0
    assert "cavity" not in layer["rule"]


def test_bad_scene_names_file_line_and_key(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("seed = 3\n[sampling]\nvoxel_size = -1.0\n")
    with pytest.raises(strata.BadInputError) as caught:
        strata.load_scene(path)
    error = caught.value
    assert isinstance(error, ValueError)
    assert str(path) in str(error)
    assert error.file == str(path) and error.line == 3 and error.key == "sampling.voxel_size"
    assert error.kind == "bad input"


def test_parse_error_names_the_source():
    with pytest.raises(ValueError, match="inline.toml"):
        strata.parse_scene("this is not toml = = 3", "inline.toml")


def test_missing_scene_file(tmp_path):
    with pytest.raises(strata.BadInputError, match="nothing-here.toml"):
        strata.load_scene(tmp_path / "nothing-here.toml")


def test_resolve_quality_matches_presets(small_scene):
    balanced = small_scene.resolve_quality()
    assert balanced["preset"] == "balanced" and balanced["voxel_size"] == small_scene.voxel_size
    fast = small_scene.resolve_quality("fast")
    assert fast["voxel_size"] > balanced["voxel_size"]
    assert small_scene.resolve_quality(quality={"mesher": "surface-nets"})["mesher"] == "surface-nets"
    with pytest.raises(strata.BadInputError) as caught:
        small_scene.resolve_quality(quality={"mesher": "marching-squares"})
    assert caught.value.key == "mesher" and caught.value.value == "marching-squares"
    with pytest.raises(strata.BadInputError, match="not a preset"):
        small_scene.resolve_quality("fastest")


ERODED = """seed = 3
[terrain]
root = "eroded"
[terrain.nodes.eroded]
type = "erode"
height = "land"
min = [-32.0, -32.0]
max = [32.0, 32.0]
cell_size = 2.0
years = %d
[terrain.nodes.land]
type = "heightfield"
amplitude = 10.0
wavelength = 40.0
"""


def test_an_erode_pass_reports_progress_and_stops_on_false():
    # The erode pass runs while the scene loads: its progress reaches the
    # callable, and False stops the load with KeyboardInterrupt (issue 41:
    # the pass could not be interrupted). Each run its own years: not cached.
    seen = []
    scene = strata.parse_scene(ERODED % 1000000, progress=seen.append)
    assert scene.has_landform and len(seen) >= 10
    assert seen == sorted(seen) and seen[-1] == 1.0
    calls = []
    with pytest.raises(KeyboardInterrupt):
        strata.parse_scene(ERODED % 1020000, progress=lambda f: calls.append(f) or len(calls) < 3)
    assert len(calls) == 3


def test_the_default_scene_has_no_place_on_the_earth():
    assert strata.default_scene().georeference is None


def test_the_cache_limit_is_settable_and_results_do_not_depend_on_it():
    scene = strata.parse_scene("""
[region]
min = [-64, -20, -64]
max = [64, 40, 64]
[terrain]
root = "caves"
[terrain.nodes.caves]
type = "worms"
cell_size = 32
""")
    points = [[x * 3.1, 1.0, -x * 2.3] for x in range(-15, 15)]
    default = strata.cache_memory_limit()
    assert default > 0
    try:
        strata.set_cache_memory_limit(1 << 20)
        assert strata.cache_memory_limit() == 1 << 20
        small = scene.field.evaluate(points)
        assert strata.cache_memory_used() >= 0
        strata.set_cache_memory_limit(0)
        assert strata.cache_memory_limit() == default
        large = scene.field.evaluate(points)
        assert (small == large).all()
    finally:
        strata.set_cache_memory_limit(0)
