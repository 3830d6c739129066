# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""The Blender add-on's headless check (issue 28, part 3), run by ctest as
Python.blender_addon:

    blender -b --factory-startup --python-use-system-env --python-exit-code 1 \
        --python python/tests/blender_addon_check.py

with PYTHONPATH at the built module. It registers the add-on, adds the default
scene's terrain through the operator (at 1 m voxels, to stay quick on two
cores) and compares it with the library in the same process, checks the
material's nodes and images, and renders a small Cycles CPU frame that must
show the terrain. Any failure raises, and Blender exits 1."""

import os
import pathlib
import sys
import tempfile
import time

import bpy
import numpy as np

import strata

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "blender"))

import strata_terrain  # noqa: E402  (python/blender, above)

VOXEL = 1.0  # metres: the default scene at 0.5 m is 1.5 M triangles, four times the work


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def registers():
    strata_terrain.register()
    check(hasattr(bpy.types, "MESH_OT_strata_terrain_add"), "the operator is not registered")
    drawn = [f for f in bpy.types.VIEW3D_MT_mesh_add._dyn_ui_initialize() if f is strata_terrain.menu_func]
    check(drawn, "Strata Terrain is not in Add > Mesh")
    check(strata_terrain.bl_info["category"] == "Add Mesh" and strata_terrain.bl_info["blender"] == (3, 4, 0),
          "bl_info")


def adds_the_default_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    started = time.perf_counter()
    result = bpy.ops.mesh.strata_terrain_add(voxel_size=VOXEL)
    elapsed = time.perf_counter() - started
    check(result == {"FINISHED"}, f"the operator returned {result}")
    obj = bpy.context.active_object
    check(obj is not None and obj.type == "MESH", "no terrain object added")

    scene = strata.default_scene()
    reference = strata.mesh(strata.sample(scene, voxel_size=VOXEL))
    mesh = obj.data
    print(f"add-on: {len(mesh.vertices)} vertices, {len(mesh.polygons)} triangles in {elapsed:.2f} s; "
          f"library: {reference.vertex_count}, {reference.triangle_count}")
    check(len(mesh.vertices) == reference.vertex_count, "vertex count differs from strata.mesh()")
    check(len(mesh.polygons) == reference.triangle_count, "triangle count differs from strata.mesh()")
    check(all(len(p.vertices) == 3 for p in mesh.polygons[:1000]), "faces are not triangles")

    # Positions: the library's, Y-up turned Z-up: (x, y, z) -> (x, -z, y).
    co = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    v = reference.vertices.astype(np.float64) + np.array(reference.origin)
    expected = np.stack((v[:, 0], -v[:, 2], v[:, 1]), axis=1)
    check(np.allclose(co, expected, atol=1e-4), "vertices are not the library's in Z-up")
    (lo, hi) = scene.region
    region_lo = np.array([lo[0], -hi[2], lo[1]])
    region_hi = np.array([hi[0], -lo[2], hi[1]])
    check(np.all(co.min(axis=0) >= region_lo - VOXEL) and np.all(co.max(axis=0) <= region_hi + VOXEL),
          f"bounding box {co.min(axis=0)}..{co.max(axis=0)} is outside the region {region_lo}..{region_hi}")
    extent = co.max(axis=0) - co.min(axis=0)
    check(extent[0] > 0.9 * (hi[0] - lo[0]) and extent[1] > 0.9 * (hi[2] - lo[2]),
          f"the terrain does not span the region: {extent}")

    # Faces point outward: the normals from the winding agree with the
    # library's (from the field's gradient, pointing out of the rock), and
    # on the top of the terrain (its upper tenth) most point up (+Z).
    face_normals = np.empty(3 * len(mesh.polygons), dtype=np.float32)
    mesh.polygons.foreach_get("normal", face_normals)
    centers = np.empty(3 * len(mesh.polygons), dtype=np.float32)
    mesh.polygons.foreach_get("center", centers)
    face_normals, centers = face_normals.reshape(-1, 3), centers.reshape(-1, 3)
    library = reference.normals[reference.triangles].sum(axis=1)
    library = np.stack((library[:, 0], -library[:, 2], library[:, 1]), axis=1)
    outward = np.mean(np.sum(face_normals * library, axis=1) > 0.0)
    top = centers[:, 2] > np.quantile(centers[:, 2], 0.9)
    up = np.mean(face_normals[top, 2] > 0.0)
    print(f"faces agreeing with the library's normals: {outward:.4f}; of the upper tenth pointing up: {up:.3f}")
    check(outward > 0.99, f"only {outward:.3f} of the faces point outward: the winding is flipped")
    check(up > 0.6, f"only {up:.2f} of the top faces point up")
    mesh.calc_normals_split()
    split = np.empty(3 * len(mesh.loops), dtype=np.float32)
    mesh.loops.foreach_get("normal", split)
    split = split.reshape(-1, 3)
    library = reference.normals[reference.triangles.ravel()]
    library = np.stack((library[:, 0], -library[:, 2], library[:, 1]), axis=1)
    agree = np.mean(np.sum(split * library, axis=1) > 0.99)
    check(agree > 0.99, f"custom normals are not the library's ({agree:.3f} agree)")
    return obj


def material_is_strata(obj):
    material = obj.data.materials[0]
    nodes = material.node_tree.nodes
    images = [n for n in nodes if n.type == "TEX_IMAGE"]
    boxes = [n for n in images if n.projection == "BOX"]
    check(len(boxes) >= 4, f"{len(boxes)} box-projected image nodes, expected albedo, mask and top ones")
    check(all(0.0 < n.projection_blend < 1.0 for n in boxes), "box blend not set from the scene's blend")
    by_name = {n.image.name.rsplit(" ", 1)[-1]: n.image for n in images}
    check({"albedo", "mask", "normal", "top_albedo", "top_mask", "top_normal"} <= set(by_name),
          f"images: {sorted(by_name)}")
    check(by_name["albedo"].colorspace_settings.name == "sRGB", "albedo is not sRGB")
    check(by_name["mask"].colorspace_settings.name == "Non-Color", "mask is not Non-Color")
    check(by_name["normal"].colorspace_settings.name == "Non-Color", "normal map is not Non-Color")
    maps = strata.default_scene().material.maps()
    pixels = np.empty(len(by_name["albedo"].pixels), dtype=np.float32)
    by_name["albedo"].pixels.foreach_get(pixels)
    pixels = np.flipud(pixels.reshape(maps["albedo"].shape))
    check(np.allclose(pixels * 255.0, maps["albedo"], atol=0.51), "albedo pixels are not the library's")
    check(any(n.type == "BSDF_PRINCIPLED" for n in nodes), "no Principled BSDF")
    groups = {n.node_tree.name for n in nodes if n.type == "GROUP"}
    check("Strata Triplanar Weights" in groups, f"groups: {groups}")
    check(material.node_tree.nodes["Principled BSDF"].inputs["Normal"].is_linked, "normal maps not connected")


def adds_layers():
    """docs/four-layers-default.toml (sand by altitude and slope, soil by
    cavity, snow by altitude, slope and noise) at 2 m voxels: each layer is
    height-blended over the base by its bands, and the cavity the soil
    reads is on the mesh."""
    path = str(HERE.parents[1] / "docs" / "four-layers-default.toml")
    result = bpy.ops.mesh.strata_terrain_add(filepath=path, voxel_size=2.0, preset="fast")
    check(result == {"FINISHED"}, f"the operator returned {result} on {path}")
    obj = bpy.context.active_object
    scene = strata.load_scene(path)
    reference = strata.mesh(strata.sample(scene, voxel_size=2.0, preset="fast"), preset="fast")
    check(len(obj.data.polygons) == reference.triangle_count, "layered scene: triangle count differs")
    check("strata_cavity" in obj.data.attributes, "no cavity attribute for the soil layer's rule")
    nodes = obj.data.materials[0].node_tree.nodes
    groups = [n.node_tree.name for n in nodes if n.type == "GROUP"]
    check(groups.count("Strata Height Blend") == 3, f"groups: {groups}")
    check(groups.count("Strata Band") == 6, f"six bands expected (2 sand, 1 soil, 2 snow + noise): {groups}")
    check(any(n.type == "ATTRIBUTE" and n.attribute_name == "strata_cavity" for n in nodes), "cavity not read")
    check(sum(n.type == "TEX_NOISE" for n in nodes) == 1, "the snow's noise mask is missing")
    bpy.data.objects.remove(obj)


def bad_scene_file_is_reported():
    """A missing scene file cancels the operator with the library's error,
    which names the file (bpy.ops raises it as RuntimeError)."""
    before = len(bpy.data.objects)
    try:
        result = bpy.ops.mesh.strata_terrain_add(filepath="/nonexistent/terrain.toml")
    except RuntimeError as error:
        check("/nonexistent/terrain.toml" in str(error), f"the error does not name the file: {error}")
    else:
        raise AssertionError(f"a missing scene file gave {result}")
    check(len(bpy.data.objects) == before, "a failed run left an object")


def renders_the_terrain(obj, out_dir):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 8
    scene.cycles.use_denoising = False
    scene.render.resolution_x, scene.render.resolution_y = 160, 90
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.world = bpy.data.worlds.new("sky")
    scene.world.color = (0.55, 0.7, 0.9)

    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 4.0
    sun.rotation_euler = (0.7, 0.2, 0.8)
    scene.collection.objects.link(sun)
    # A camera on the scene's orbit (azimuth 30, elevation 35 degrees), looking at the centre.
    cam_data = bpy.data.cameras.new("camera")
    cam_data.lens_unit = "FOV"
    cam_data.angle = np.radians(45.0)
    camera = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(camera)
    azimuth, elevation, distance = np.radians(30.0), np.radians(35.0), 260.0
    camera.location = (distance * np.cos(elevation) * np.sin(azimuth),
                       -distance * np.cos(elevation) * np.cos(azimuth),
                       distance * np.sin(elevation))
    direction = -np.array(camera.location)
    camera.rotation_euler = direction_to_euler(direction)
    scene.camera = camera

    path = os.path.join(out_dir, "terrain.png")
    scene.render.filepath = path
    started = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"Cycles CPU 160x90, 8 samples: {time.perf_counter() - started:.2f} s")
    check(os.path.exists(path), "no PNG written")
    image = bpy.data.images.load(path)
    pixels = np.empty(len(image.pixels), dtype=np.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(90, 160, 4)[..., :3]
    # The sky is the world colour, flat: the terrain is what differs from it.
    not_sky = np.linalg.norm(rgb - sky_pixel(rgb), axis=2) > 0.08
    share = float(np.mean(not_sky))
    print(f"render: std {rgb.std():.3f}, {share:.2f} of the pixels not sky, mean {rgb.mean(axis=(0, 1))}")
    check(rgb.std() > 0.03, "the render is flat")
    check(share > 0.3, f"only {share:.2f} of the frame is terrain")
    # Terrain colour: rock and grass are warmer/greener than the blue sky.
    terrain_rgb = rgb[not_sky].mean(axis=0)
    check(terrain_rgb[2] < terrain_rgb[1] or terrain_rgb[2] < terrain_rgb[0],
          f"the terrain's mean colour {terrain_rgb} is sky blue")


def sky_pixel(rgb):
    """The colour of the frame's top row (the sky behind the terrain)."""
    return rgb[-1].mean(axis=0)  # Blender's pixels are bottom row first: -1 is the top


def direction_to_euler(direction):
    from mathutils import Vector
    return Vector(direction).to_track_quat("-Z", "Y").to_euler()


def main():
    started = time.perf_counter()
    registers()
    obj = adds_the_default_scene()
    material_is_strata(obj)
    adds_layers()
    bad_scene_file_is_reported()
    with tempfile.TemporaryDirectory() as out_dir:
        renders_the_terrain(obj, out_dir)
    strata_terrain.unregister()
    check(not hasattr(bpy.types, "MESH_OT_strata_terrain_add"), "the operator is still registered")
    print(f"blender_addon_check: all passed in {time.perf_counter() - started:.1f} s")


try:
    main()
except Exception:
    import traceback
    traceback.print_exc()
    sys.exit(1)
