# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Renders docs/blender-terrain.png: the default scene added by the Strata
Terrain add-on, with its material, in Cycles on the CPU.

    PYTHONPATH=build/python blender -b --factory-startup --python-use-system-env \
        --python python/blender/render_picture.py -- OUT.png [WIDTH HEIGHT SAMPLES VOXEL [SCENE.toml]]

Prints the add-on's timings (sample, mesh, Blender mesh, material)."""

import math
import pathlib
import sys
import time

import bpy
from mathutils import Vector

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import strata_terrain  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out = argv[0] if argv else "blender-terrain.png"
width, height, samples = (int(v) for v in (argv[1:4] if len(argv) >= 4 else (800, 450, 24)))
voxel = float(argv[4]) if len(argv) >= 5 else 0.0
scene_file = argv[5] if len(argv) >= 6 else ""

strata_terrain.register()
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
started = time.perf_counter()
bpy.ops.mesh.strata_terrain_add(voxel_size=voxel, filepath=scene_file)
print(f"add-on: {scene_file or 'the default scene'} added in {time.perf_counter() - started:.2f} s")

scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.compression = 100
scene.view_settings.view_transform = "Standard"

# Sky and sun from the default scene's [lighting] (sun_direction is Y-up).
strata = __import__("strata")
strata_scene = strata.load_scene(scene_file) if scene_file else strata.default_scene()
lighting = strata_scene.lighting
world = bpy.data.worlds.new("Strata sky")
world.color = lighting["sky_color"]
scene.world = world
sx, sy, sz = lighting["sun_direction"]
sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
sun.data.energy = 3.0
sun.data.color = [c / max(lighting["sun_color"]) for c in lighting["sun_color"]]
sun.rotation_euler = Vector((sx, -sz, sy)).to_track_quat("Z", "Y").to_euler()  # a sun light shines along -Z
scene.collection.objects.link(sun)

# The scene's orbit camera: azimuth and elevation around the region's centre.
camera_settings = strata_scene.camera
cam = bpy.data.cameras.new("Camera")
cam.lens_unit = "FOV"
cam.angle = math.radians(camera_settings["fov"])
camera = bpy.data.objects.new("Camera", cam)
scene.collection.objects.link(camera)
azimuth, elevation = math.radians(camera_settings["azimuth"]), math.radians(camera_settings["elevation"])
distance = 600.0
target = Vector((8.0, 0.0, -22.0))
camera.location = target + distance * Vector((math.cos(elevation) * math.sin(azimuth),
                                              -math.cos(elevation) * math.cos(azimuth), math.sin(elevation)))
camera.rotation_euler = (target - camera.location).to_track_quat("-Z", "Y").to_euler()
scene.camera = camera

scene.render.filepath = out
started = time.perf_counter()
bpy.ops.render.render(write_still=True)
print(f"Cycles CPU {width}x{height}, {samples} samples: {time.perf_counter() - started:.1f} s")
