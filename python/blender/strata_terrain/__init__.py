# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Strata Terrain: Add > Mesh > Strata Terrain (issue 28, part 3).

Runs the Strata library in-process (`import strata`, the pybind11 module of
python/), turns its mesh into a Blender mesh (terrain_mesh.py) and gives it a
node material that reproduces Strata's triplanar look with Blender's own nodes
(terrain_material.py). docs/python.md, "Blender add-on", says how to install
it and what the material approximates.
"""

bl_info = {
    "name": "Strata Terrain",
    "author": "The Strata authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Add > Mesh > Strata Terrain",
    "description": "Procedural voxel terrain from a Strata scene file, with Strata's triplanar material",
    "category": "Add Mesh",
}

import time

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import terrain_material, terrain_mesh

PRESETS = [
    ("SCENE", "Scene's", "The scene's [quality] preset and knobs (balanced where it sets none), as `strata generate`"),
    ("fast", "Fast", "Coarse voxels (1 m on the default scene), surface nets, simplified"),
    ("balanced", "Balanced", "The scene's own voxel size, the volume mesher (Strata's default)"),
    ("accurate", "Accurate", "Finer voxels and meshing: slowest"),
]

MESHERS = [
    ("PRESET", "Preset's", "The mesher the preset (and the scene's [quality]) chooses"),
    ("volume", "Volume", "Dual mesher with sharp features, optionally adaptive"),
    ("surface-nets", "Surface Nets", "Each vertex at its cell's mean crossing: smooth, fast"),
    ("dual-contouring", "Dual Contouring", "Vertices from the QEF of the cell's crossings"),
]


def import_strata():
    """The library, or an error that says how to make it importable."""
    try:
        import strata
    except ImportError as error:
        raise RuntimeError(
            "Strata's Python module is not importable from Blender's Python: install it with "
            "`cmake --install build` (Debian's Blender finds /usr/local/lib/python3.11/dist-packages) "
            f"or put build/python on PYTHONPATH and start Blender with --python-use-system-env ({error})"
        ) from error
    return strata


class BlenderProgress:
    """strata's progress callable on Blender's progress bar (0..1000 steps:
    the window manager redraws only when the integer changes)."""

    def __init__(self, window_manager, start, end):
        self.wm = window_manager
        self.start = start
        self.end = end

    def __call__(self, fraction):
        if self.wm is not None:
            self.wm.progress_update(int(1000 * (self.start + (self.end - self.start) * fraction)))
        return None


class STRATA_OT_add_terrain(bpy.types.Operator):
    """Generate a Strata scene's terrain and add it as a mesh with Strata's triplanar material"""

    bl_idname = "mesh.strata_terrain_add"
    bl_label = "Strata Terrain"
    bl_options = {"REGISTER", "UNDO"}

    filepath: StringProperty(
        name="Scene File", subtype="FILE_PATH", default="",
        description="A Strata scene (.toml); empty for the built-in default scene")
    use_scene_seed: BoolProperty(name="Scene's Seed", default=True, description="Use the seed the scene file sets")
    seed: IntProperty(name="Seed", default=1, min=0, description="The seed when Scene's Seed is off")
    voxel_size: FloatProperty(
        name="Voxel Size", default=0.0, min=0.0, soft_max=8.0, unit="LENGTH",
        description="Metres per voxel; 0 for the scene's (or the preset's) own")
    preset: EnumProperty(name="Preset", items=PRESETS, default="SCENE")
    mesher: EnumProperty(name="Mesher", items=MESHERS, default="PRESET")
    with_material: BoolProperty(name="Material", default=True, description="Build Strata's triplanar material")

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "filepath")
        row = layout.row()
        row.prop(self, "use_scene_seed")
        sub = row.row()
        sub.enabled = not self.use_scene_seed
        sub.prop(self, "seed")
        layout.prop(self, "voxel_size")
        layout.prop(self, "preset")
        layout.prop(self, "mesher")
        layout.prop(self, "with_material")

    def execute(self, context):
        try:
            obj, timings = self.add_terrain(context)
        except Exception as error:  # the library's errors name file, line and key: show them as they are
            self.report({"ERROR"}, f"Strata Terrain: {error}")
            return {"CANCELLED"}
        self.report({"INFO"}, "Strata Terrain: " + ", ".join(f"{k} {v:.2f} s" for k, v in timings.items()))
        return {"FINISHED"}

    def add_terrain(self, context):
        strata = import_strata()
        wm = context.window_manager
        timings = {}
        started = time.perf_counter()
        wm.progress_begin(0, 1000)
        try:
            scene = strata.load_scene(bpy.path.abspath(self.filepath)) if self.filepath else strata.default_scene()
            # Sampling is most of the work; meshing and building the Blender mesh share the rest.
            preset = None if self.preset == "SCENE" else self.preset
            grid = strata.sample(
                scene,
                seed=None if self.use_scene_seed else self.seed,
                preset=preset,
                voxel_size=self.voxel_size if self.voxel_size > 0.0 else None,
                progress=BlenderProgress(wm, 0.0, 0.8))
            timings["sample"] = time.perf_counter() - started
            mark = time.perf_counter()
            mesh = strata.mesh(grid, preset=preset, mesher=None if self.mesher == "PRESET" else self.mesher)
            timings["mesh"] = time.perf_counter() - mark
            wm.progress_update(850)
            mark = time.perf_counter()
            name = bpy.path.display_name_from_filepath(self.filepath) if self.filepath else "Strata Terrain"
            data = terrain_mesh.build_mesh(mesh, name)
            timings["blender mesh"] = time.perf_counter() - mark
            wm.progress_update(950)
            if self.with_material:
                mark = time.perf_counter()
                data.materials.append(terrain_material.build_material(scene.material, name))
                timings["material"] = time.perf_counter() - mark
            obj = bpy.data.objects.new(name, data)
            context.collection.objects.link(obj)
            for other in context.selected_objects:
                other.select_set(False)
            obj.select_set(True)
            context.view_layer.objects.active = obj
        finally:
            wm.progress_end()
        timings["total"] = time.perf_counter() - started
        return obj, timings


def menu_func(self, context):
    self.layout.operator(STRATA_OT_add_terrain.bl_idname, text="Strata Terrain", icon="MESH_GRID")


def register():
    bpy.utils.register_class(STRATA_OT_add_terrain)
    bpy.types.VIEW3D_MT_mesh_add.append(menu_func)


def unregister():
    bpy.types.VIEW3D_MT_mesh_add.remove(menu_func)
    bpy.utils.unregister_class(STRATA_OT_add_terrain)
