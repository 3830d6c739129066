# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

import json
import os
import signal
import threading

import numpy as np
import pytest

import strata
from conftest import run_cli, ticks_during


def test_render_is_the_terrain(small_scene, small_mesh):
    image = strata.render(small_scene, small_mesh, size=(96, 64))
    assert image.shape == (64, 96, 4) and image.dtype == np.uint8
    assert np.all(image[..., 3] == 255)
    # Not one flat colour: terrain in front of the sky.
    assert len(np.unique(image[..., :3].reshape(-1, 3), axis=0)) > 100
    normals = strata.render(small_scene, small_mesh, size=(96, 64), debug_view="normals")
    assert not np.array_equal(normals, image)


def test_render_matches_the_cli_snapshot(tmp_path, small_scene_text):
    scene_file = tmp_path / "small.toml"
    scene_file.write_text(small_scene_text)
    run_cli("generate", scene_file, "-o", tmp_path / "cli", "--backend", "cpu", "--size", "120x80", "-q")
    scene = strata.load_scene(scene_file)
    image = strata.render(scene, strata.mesh(strata.sample(scene)), backend="cpu", size=(120, 80))
    assert np.array_equal(image, strata.read_image(tmp_path / "cli" / "snapshot.png"))
    strata.write_image(image, tmp_path / "again.png")
    assert np.array_equal(strata.read_image(tmp_path / "again.png"), image)


def test_render_refuses_bad_arguments(small_scene, small_mesh):
    with pytest.raises(strata.BadInputError):
        strata.render(small_scene, small_mesh, size=(0, 10))
    with pytest.raises(strata.BadInputError):
        strata.render(small_scene, small_mesh, backend="vulkan")
    with pytest.raises(strata.BadInputError, match="cave"):
        strata.render(small_scene, small_mesh, view="cave")


def test_world_streams_digs_and_fills(small_scene):
    world = strata.World(small_scene, chunk_size=16, levels=2, view_radius=24.0, threads=2)
    world.move_to((0.0, 0.0, 0.0))
    world.wait_idle()
    updates = world.poll()
    assert world.stats["holes"] == 0 and world.stats["pending"] == 0  # the view is whole once idle
    meshes = {key: mesh for key, mesh in updates if mesh is not None}
    assert meshes, "no chunk meshes after the first view filled"
    key, mesh = next(iter(meshes.items()))
    assert len(key) == 4 and mesh.triangle_count > 0
    assert not mesh.vertices.flags.writeable  # shared with the world
    assert world.chunk_mesh(key) is not None
    assert key in world.resident_chunks()

    hit = world.raycast((0.0, 30.0, 0.0), (0.0, -1.0, 0.0), 100.0)
    assert hit is not None and abs(world.density(hit["position"])) < 1e-3
    before = world.density(hit["position"])
    result = world.dig(strata.EditShape.sphere(hit["position"], 3.0))
    assert result["changed_voxels"] > 0 and result["marked_chunks"]
    assert world.density(hit["position"]) > before + 1.0
    world.wait_idle()
    assert any(k in map(tuple, result["marked_chunks"]) for k, _ in world.poll())
    filled = world.fill(strata.EditShape.box(hit["position"], (2.0, 2.0, 2.0)))
    assert filled["changed_voxels"] > 0 and world.density(hit["position"]) < 0
    assert world.stats["resident"] > 0
    with pytest.raises(strata.BadInputError):
        strata.EditShape.sphere((0, 0, 0), -1.0)


def test_world_meshes_ahead_of_a_moving_point(small_scene):
    stats = {}
    for look_ahead in (True, False):
        world = strata.World(small_scene, chunk_size=16, levels=2, view_radius=24.0, threads=2,
                             look_ahead=look_ahead)
        for x in range(0, 7):  # heading +x inside the chunk at 0..8 m
            world.move_to((float(x), 0.0, 0.0))
        world.wait_idle()
        stats[look_ahead] = world.stats
    assert stats[True]["prefetch_held"] > 0 and stats[True]["prefetched"] == 0
    assert stats[False]["prefetch_held"] == 0
    assert stats[True]["resident"] == stats[False]["resident"]


def test_bake_writes_a_tileset_like_the_cli(tmp_path, small_scene_text):
    scene_file = tmp_path / "small.toml"
    scene_file.write_text(small_scene_text)
    scene = strata.load_scene(scene_file)
    fractions = []
    summary = strata.bake(scene, tmp_path / "py", tile_size=12.0, lods=2, threads=2, progress=fractions.append)
    assert summary["tiles"] == summary["baked"] > 0 and summary["missing"] == 0
    assert fractions and fractions[-1] == 1.0 and fractions == sorted(fractions)
    run_cli("bake", scene_file, "-o", tmp_path / "cli", "--tile-size", 12, "--lods", 2, "-q")
    py_manifest = json.loads((tmp_path / "py" / "manifest.json").read_text())
    cli_manifest = json.loads((tmp_path / "cli" / "manifest.json").read_text())
    # Every tile's files, with their SHA-256, are the CLI's.
    assert [(t["levels"], t["grid"]) for t in py_manifest["tiles"]] == \
        [(t["levels"], t["grid"]) for t in cli_manifest["tiles"]]
    assert (tmp_path / "py" / "tileset.json").read_bytes() == (tmp_path / "cli" / "tileset.json").read_bytes()


def test_progress_false_stops_with_keyboard_interrupt():
    scene = strata.default_scene()
    with pytest.raises(KeyboardInterrupt):
        strata.sample(scene, progress=lambda fraction: fraction < 0.2)


def test_progress_exception_propagates():
    def explode(fraction):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        strata.sample(strata.default_scene(), progress=explode)


def test_ctrl_c_stops_sampling():
    scene = strata.default_scene()
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            strata.sample(scene, quality={"voxel_size": 0.25})
    finally:
        timer.cancel()


def test_sample_releases_the_gil():
    ticks, seconds = ticks_during(lambda: strata.sample(strata.default_scene()))
    assert ticks >= 10, f"the other thread ran {ticks} times in {seconds:.2f} s"


def test_memory_budget_is_bad_input(small_scene):
    with pytest.raises(strata.BadInputError, match="memory"):
        strata.sample(small_scene, max_memory=1000)


def test_gl_backend_agrees_with_the_cpu_renderer(small_scene, small_mesh):
    """OpenGL through EGL (llvmpipe where there is no GPU) against the CPU
    reference renderer: the same picture within the renderers' parity."""
    cpu = strata.render(small_scene, small_mesh, backend="cpu", size=(160, 96)).astype(np.float64)
    gl = strata.render(small_scene, small_mesh, backend="gl", size=(160, 96)).astype(np.float64)
    mse = np.mean((cpu[..., :3] - gl[..., :3]) ** 2)
    psnr = 10.0 * np.log10(255.0 ** 2 / mse) if mse > 0 else np.inf
    assert psnr >= 30.0, f"GL against CPU: {psnr:.1f} dB"


def test_progress_must_be_callable_and_answer_a_truth_value(small_scene):
    with pytest.raises(strata.BadInputError, match="callable"):
        strata.sample(small_scene, progress=42)

    class NoTruth:
        def __bool__(self):
            raise ValueError("no truth here")

    with pytest.raises(TypeError, match="True or False"):
        strata.sample(small_scene, progress=lambda f: NoTruth())
