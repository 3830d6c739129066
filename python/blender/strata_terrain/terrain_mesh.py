# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""A strata.Mesh as a Blender mesh: bulk array copies only (foreach_set), no
Python loop over vertices or triangles."""

import bpy
import numpy as np


def to_blender_axes(points):
    """Strata is Y-up, Blender Z-up: (x, y, z) -> (x, -z, y). A rotation of
    +90 degrees about X (determinant +1), so triangle winding and the
    outward side of every face stay as they are."""
    return np.stack((points[:, 0], -points[:, 2], points[:, 1]), axis=1)


def build_mesh(strata_mesh, name):
    """A new bpy.types.Mesh with the vertices (origin added, in double so a far
    origin rounds once), triangles, smooth shading and the library's normals
    as custom split normals."""
    vertices = strata_mesh.vertices.astype(np.float64) + np.asarray(strata_mesh.origin, dtype=np.float64)
    vertices = to_blender_axes(vertices).astype(np.float32)
    triangles = np.ascontiguousarray(strata_mesh.triangles, dtype=np.int32)
    vertex_count = len(vertices)
    triangle_count = len(triangles)

    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(vertex_count)
    mesh.vertices.foreach_set("co", vertices.ravel())
    mesh.loops.add(3 * triangle_count)
    mesh.loops.foreach_set("vertex_index", triangles.ravel())
    mesh.polygons.add(triangle_count)
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * triangle_count, 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(triangle_count, 3, dtype=np.int32))
    mesh.polygons.foreach_set("use_smooth", np.ones(triangle_count, dtype=bool))
    mesh.update(calc_edges=True)

    normals = strata_mesh.normals
    if normals is not None:
        # Custom split normals need auto smooth on (Blender 3.x); the library's
        # normals (from the field's gradient by default) are smoother than the
        # ones Blender would average from the faces.
        mesh.use_auto_smooth = True
        mesh.auto_smooth_angle = np.pi
        mesh.normals_split_custom_set_from_vertices(to_blender_axes(np.asarray(normals, dtype=np.float32)))
    add_vertex_attributes(mesh, strata_mesh)
    return mesh


# The per-vertex values [[layer]] rules read (docs/rendering.md), as float
# point attributes the material's Attribute nodes read by these names.
SURFACE_ATTRIBUTES = ("strata_cavity", "strata_cover")
LANDFORM_ATTRIBUTES = ("strata_flow", "strata_wear", "strata_deposition", "strata_water")
ROCK_ATTRIBUTES = ("strata_hardness", "strata_bed")


def add_vertex_attributes(mesh, strata_mesh):
    """Cavity and cover (mesh.surface), the landform masks (mesh.landform) and
    the rock masks (mesh.rock), when the library computed them (only for
    scenes whose layers read them)."""
    for names, values in ((SURFACE_ATTRIBUTES, strata_mesh.surface), (LANDFORM_ATTRIBUTES, strata_mesh.landform),
                          (ROCK_ATTRIBUTES, strata_mesh.rock)):
        if values is None:
            continue
        for column, name in enumerate(names):
            attribute = mesh.attributes.new(name, "FLOAT", "POINT")
            attribute.data.foreach_set("value", np.ascontiguousarray(values[:, column], dtype=np.float32))
