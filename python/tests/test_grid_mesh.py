# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

import numpy as np
import pytest

import strata
from conftest import run_cli


def test_grid_counts_and_dense_copy(small_grid, small_scene):
    assert small_grid.active_voxel_count > 1000
    assert small_grid.voxel_size == small_scene.voxel_size
    assert small_grid.seed == small_scene.seed
    (lo, hi) = small_grid.index_bounds
    dense = small_grid.dense()
    assert dense.dtype == np.float32
    assert dense.shape == tuple(h - l + 1 for l, h in zip(lo, hi))
    assert np.all(np.abs(dense) <= small_grid.background)
    # Inside the band the grid holds the field's value (as float).
    i, j, k = np.argwhere(np.abs(dense) < 0.5 * small_grid.background)[0]
    world = [(lo[a] + idx) * small_grid.voxel_size for a, idx in enumerate((i, j, k))]
    assert dense[i, j, k] == np.float32(small_scene.field.density(world))
    small = small_grid.dense((0, 0, 0), (1, 2, 3))
    assert small.shape == (2, 3, 4)
    with pytest.raises(strata.BadInputError):
        small_grid.dense((0, 0, 0), (-1, 0, 0))


def test_mesh_arrays_view_the_mesh_without_copies(small_mesh):
    v, t, n = small_mesh.vertices, small_mesh.triangles, small_mesh.normals
    assert v.dtype == np.float32 and v.shape == (small_mesh.vertex_count, 3)
    assert t.dtype == np.uint32 and t.shape == (small_mesh.triangle_count, 3)
    assert n.shape == v.shape
    assert not v.flags.owndata and not t.flags.owndata
    # Two reads are the same memory: the mesh's own buffer.
    assert v.__array_interface__["data"][0] == small_mesh.vertices.__array_interface__["data"][0]
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-4)
    assert t.max() < small_mesh.vertex_count


def test_arrays_keep_the_mesh_alive(small_grid):
    vertices = strata.mesh(small_grid).vertices  # the Mesh object is gone
    copy = vertices.copy()
    strata.mesh(small_grid, mesher="surface-nets")  # reuse freed memory, if any were freed
    assert np.array_equal(vertices, copy)


def test_meshers_and_overrides(small_grid):
    volume = strata.mesh(small_grid)
    nets = strata.mesh(small_grid, mesher="surface-nets")
    assert nets.triangle_count > 0
    # Both are dual meshers on the same lattice (the same cells, so often the
    # same counts); surface nets places each vertex at its cell's mean crossing.
    assert not np.array_equal(nets.vertices, volume.vertices)
    simplified = strata.mesh(small_grid, simplify=0.25)
    assert simplified.triangle_count < 0.5 * volume.triangle_count
    with pytest.raises(strata.BadInputError) as caught:
        strata.mesh(small_grid, quality={"voxel_size": 1.0})
    assert caught.value.key == "voxel_size"
    with pytest.raises(strata.BadInputError):
        strata.mesh(small_grid, adaptivity=2.0)


def test_same_bytes_as_strata_generate(tmp_path, small_scene_text):
    scene_file = tmp_path / "small.toml"
    scene_file.write_text(small_scene_text)
    run_cli("generate", scene_file, "-o", tmp_path / "cli", "--no-snapshot", "-q")
    scene = strata.load_scene(scene_file)
    grid = strata.sample(scene)
    (tmp_path / "py").mkdir()
    grid.save(tmp_path / "py" / "terrain.vdb")
    strata.mesh(grid).save(tmp_path / "py" / "terrain.glb")
    for name in ("terrain.vdb", "terrain.glb"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_every_mesh_format_round_trips(tmp_path, small_mesh):
    for ext in ("glb", "ply", "obj", "stl", "off"):
        path = tmp_path / f"mesh.{ext}"
        small_mesh.save(path)
        back = strata.read_mesh(path)
        assert back.triangle_count == small_mesh.triangle_count, ext
        world = back.vertices.astype(np.float64) + np.array(back.origin)
        original = small_mesh.vertices.astype(np.float64) + np.array(small_mesh.origin)
        assert abs(world.min() - original.min()) < 1e-3 and abs(world.max() - original.max()) < 1e-3, ext


def test_mesh_from_arrays(tmp_path):
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1]], dtype=np.float32)
    mesh = strata.Mesh(vertices, [[0, 2, 1]], origin=(1e6, 0.0, 0.0))
    assert mesh.triangle_count == 1 and mesh.origin == (1e6, 0.0, 0.0) and mesh.normals is None
    mesh.save(tmp_path / "one.obj")
    with pytest.raises(strata.BadInputError, match="names vertex 3"):
        strata.Mesh(vertices, [[0, 1, 3]])


def test_write_failure_is_an_oserror(tmp_path, small_mesh):
    (tmp_path / "file").write_text("in the way")
    with pytest.raises(strata.FileError) as caught:
        small_mesh.save(tmp_path / "file" / "mesh.glb")
    assert isinstance(caught.value, OSError)
    assert caught.value.filename and "file" in caught.value.filename


def test_bad_extension(tmp_path, small_mesh):
    with pytest.raises(strata.BadInputError, match=".xyz"):
        small_mesh.save(tmp_path / "mesh.xyz")


def test_read_grid_and_mesh_it(tmp_path, small_grid):
    small_grid.save(tmp_path / "g.vdb")
    grid = strata.read_grid(tmp_path / "g.vdb")
    assert grid.active_voxel_count == small_grid.active_voxel_count and grid.scene is None
    mesh = strata.mesh(grid)
    assert mesh.triangle_count == strata.mesh(small_grid).triangle_count
    with pytest.raises(strata.BadInputError, match="field"):
        strata.mesh(grid, normals="field")
