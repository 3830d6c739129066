# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Strata's triplanar material (shaders/TriplanarShading.h,
shaders/TriplanarMaterial.h, shaders/TerrainLayers.h) rebuilt from Blender's
own shader nodes, so it renders in Cycles and Eevee and can be edited.

What is exact and what is approximated (docs/python.md says the same):
- albedo and MOHS mask: Image Texture nodes in BOX projection. Blender's box
  blend is one 0..1 softness, not Strata's |n| - offset, ^exponent: the
  blend is fitted (box_blend()) to Strata's weights between two axes;
- the top maps over the sides, and the layers over the base, use Strata's own
  weights and height blends, computed with Math nodes (node groups below);
- normal maps: per axis, like Strata (no tangent space), three flat
  projections at the box projection's own UVs, added to the surface normal
  (UDN; Strata defaults to whiteout, which differs little at these strengths);
- MOHS: metallic from R, occlusion (G) multiplies the albedo (Strata darkens
  only the indirect light), smoothness from A: Roughness = 1 - A * smoothness.
- layers: painter's order and the height blend exactly (two at a time);
  bands on altitude and slope from the geometry, on cavity, cover and the
  landform masks from the mesh's attributes; the noise mask is Blender's
  Noise Texture at the same frequency (not Strata's pattern).
Left out: detail maps, emission, anti-tiling, biplanar, the layers' own
normal maps and top maps.
"""

import math

import bpy
import numpy as np

# ---------------------------------------------------------------------------
# Images


def make_image(name, pixels, color_space):
    """A packed Blender image from an (h, w, 4) uint8 array, top row first
    (Blender stores the bottom row first, as floats)."""
    height, width = pixels.shape[:2]
    image = bpy.data.images.new(name, width, height, alpha=True)
    image.colorspace_settings.name = color_space
    # The mask's alpha is data (smoothness): never premultiply it into RGB.
    image.alpha_mode = "CHANNEL_PACKED"
    image.pixels.foreach_set((np.flipud(pixels).astype(np.float32) / 255.0).ravel())
    image.pack()  # kept inside the .blend: the maps are generated, there is no file
    return image


def material_images(settings, prefix):
    """The material's maps as images: albedo sRGB, everything else data."""
    images = {}
    for key, pixels in settings.maps().items():
        color_space = "sRGB" if key.endswith("albedo") or key == "emission" else "Non-Color"
        images[key] = make_image(f"{prefix} {key}", pixels, color_space)
    return images


# ---------------------------------------------------------------------------
# Strata's blend weights and Blender's box blend


def strata_weights_2d(angle, offset, exponent):
    """Strata's X weight for a normal at `angle` from X towards Z (the third
    component 0): pow(saturate(|n| - offset), exponent), normalised."""
    a = np.clip(np.abs(np.cos(angle)) - offset, 0.0, 1.0) ** exponent
    b = np.clip(np.abs(np.sin(angle)) - offset, 0.0, 1.0) ** exponent
    return a / np.maximum(a + b, 1e-30)


def blender_box_weights_2d(angle, blend):
    """Blender's BOX projection X weight for the same normals (Cycles'
    svm_node_tex_image_box between two axes)."""
    x, z = np.abs(np.cos(angle)), np.abs(np.sin(angle))
    ratio = x / (x + z)
    if blend <= 0.0:
        return (ratio > 0.5).astype(np.float64)
    return np.clip((ratio - 0.5 * (1.0 - blend)) / blend, 0.0, 1.0)


def box_blend(offset, exponent):
    """The box blend (0..1) whose weights are closest, in the least-squares
    sense over normals from one axis to the next, to Strata's for
    blend_offset and blend_exponent: 0.25 and 4 (the default scene) give
    0.205, whose weights are within 0.063 of Strata's at every angle."""
    angles = np.linspace(0.0, 0.5 * math.pi, 181)
    target = strata_weights_2d(angles, offset, exponent)
    candidates = np.linspace(0.0, 1.0, 201)
    errors = [np.sum((blender_box_weights_2d(angles, b) - target) ** 2) for b in candidates]
    return float(candidates[int(np.argmin(errors))])


# ---------------------------------------------------------------------------
# Node helpers


class Builder:
    """Adds and links nodes in one node tree, laid out in columns."""

    def __init__(self, tree):
        self.tree = tree
        self.nodes = tree.nodes
        self.links = tree.links

    def node(self, kind, x=0, y=0, **settings):
        node = self.nodes.new(kind)
        node.location = (x, y)
        for key, value in settings.items():
            setattr(node, key, value)
        return node

    def link(self, output, node_input):
        self.links.new(output, node_input)

    def feed(self, socket, value):
        """A socket's value: a link from an output socket, or a constant."""
        if isinstance(value, bpy.types.NodeSocket):
            self.link(value, socket)
        else:
            socket.default_value = value

    def math(self, operation, a, b=None, c=None, x=0, y=0, clamp=False):
        node = self.node("ShaderNodeMath", x, y, operation=operation, use_clamp=clamp)
        for socket, value in zip(node.inputs, (a, b, c)):
            if value is not None:
                self.feed(socket, value)
        return node.outputs[0]

    def lerp(self, a, b, t, x=0, y=0):
        """a + (b - a) * t."""
        return self.math("MULTIPLY_ADD", self.math("SUBTRACT", b, a, x=x, y=y), t, a, x=x + 160, y=y)

    def mix_color(self, a, b, factor, x=0, y=0, blend_type="MIX"):
        node = self.node("ShaderNodeMixRGB", x, y, blend_type=blend_type)
        self.feed(node.inputs["Fac"], factor)
        self.feed(node.inputs["Color1"], a)
        self.feed(node.inputs["Color2"], b)
        return node.outputs["Color"]

    def separate(self, vector, x=0, y=0):
        node = self.node("ShaderNodeSeparateXYZ", x, y)
        self.feed(node.inputs[0], vector)
        return node.outputs

    def combine(self, vx, vy, vz, x=0, y=0):
        node = self.node("ShaderNodeCombineXYZ", x, y)
        for socket, value in zip(node.inputs, (vx, vy, vz)):
            self.feed(socket, value)
        return node.outputs[0]


def new_group(name, inputs, outputs):
    """An empty shader node group with typed sockets (Blender 3.x API)."""
    group = bpy.data.node_groups.new(name, "ShaderNodeTree")
    for socket_type, socket_name in inputs:
        group.inputs.new(socket_type, socket_name)
    for socket_type, socket_name in outputs:
        group.outputs.new(socket_type, socket_name)
    b = Builder(group)
    group_in = b.node("NodeGroupInput", -800, 0)
    group_out = b.node("NodeGroupOutput", 1400, 0)
    return group, b, group_in.outputs, group_out.inputs


# ---------------------------------------------------------------------------
# Node groups: one per formula of the shared shading headers


def weights_group():
    """triplanarWeightsHeight(): w = saturate(|n| - offset) * mix(1, height,
    height_strength), raised to exponent, normalised (TriplanarShading.h).
    Axes are Blender's; the formula treats them alike."""
    name = "Strata Triplanar Weights"
    if name in bpy.data.node_groups:
        return bpy.data.node_groups[name]
    group, b, gin, gout = new_group(name, [
        ("NodeSocketVector", "Normal"), ("NodeSocketFloat", "Offset"), ("NodeSocketFloat", "Exponent"),
        ("NodeSocketFloat", "Height X"), ("NodeSocketFloat", "Height Y"), ("NodeSocketFloat", "Height Z"),
        ("NodeSocketFloat", "Height Strength"),
    ], [("NodeSocketFloat", "X"), ("NodeSocketFloat", "Y"), ("NodeSocketFloat", "Z")])
    n = b.separate(gin["Normal"], -600, 0)
    raw = []
    for i, axis in enumerate("XYZ"):
        y = 300 - 300 * i
        a = b.math("ABSOLUTE", n[i], x=-400, y=y)
        base = b.math("MAXIMUM", b.math("SUBTRACT", a, gin["Offset"], x=-240, y=y), 0.0, x=-80, y=y)
        # mix(1, h, s) = (h - 1) * s + 1
        height = b.math("MULTIPLY_ADD", b.math("SUBTRACT", gin[f"Height {axis}"], 1.0, x=-240, y=y - 120),
                        gin["Height Strength"], 1.0, x=-80, y=y - 120)
        raw.append(b.math("POWER", b.math("MULTIPLY", base, height, x=100, y=y), gin["Exponent"], x=260, y=y))
    total = b.math("MAXIMUM", b.math("ADD", b.math("ADD", raw[0], raw[1], x=440, y=-400), raw[2], x=600, y=-400),
                   1e-20, x=760, y=-400)
    for i, axis in enumerate("XYZ"):
        b.link(b.math("DIVIDE", raw[i], total, x=1000, y=300 - 300 * i), gout[axis])
    return group


def band_group():
    """bandWeight() of TerrainLayers.h: 1 inside [min, max], smoothstep ramps
    `softness` wide outside each bound, 0 beyond. The two ramps are Map Range
    nodes in smoothstep mode; the falling one maps [max, max + softness] to
    [1, 0] (smoothstep(1 - u) = 1 - smoothstep(u)). An unbounded side (Has
    Min or Has Max 0) is 1: Strata's +-1e30 would make Map Range's input
    range empty in single precision, and Map Range gives 0 for that."""
    name = "Strata Band"
    if name in bpy.data.node_groups:
        return bpy.data.node_groups[name]
    group, b, gin, gout = new_group(name, [
        ("NodeSocketFloat", "Value"), ("NodeSocketFloat", "Min"), ("NodeSocketFloat", "Max"),
        ("NodeSocketFloat", "Softness"), ("NodeSocketFloat", "Has Min"), ("NodeSocketFloat", "Has Max"),
    ], [("NodeSocketFloat", "Weight")])
    soft = b.math("MAXIMUM", gin["Softness"], 1e-6, x=-600, y=-200)
    up = b.node("ShaderNodeMapRange", -200, 200, interpolation_type="SMOOTHSTEP")
    b.link(gin["Value"], up.inputs["Value"])
    b.link(b.math("SUBTRACT", gin["Min"], soft, x=-400, y=200), up.inputs["From Min"])
    b.link(gin["Min"], up.inputs["From Max"])
    down = b.node("ShaderNodeMapRange", -200, -200, interpolation_type="SMOOTHSTEP")
    b.link(gin["Value"], down.inputs["Value"])
    b.link(gin["Max"], down.inputs["From Min"])
    b.link(b.math("ADD", gin["Max"], soft, x=-400, y=-200), down.inputs["From Max"])
    down.inputs["To Min"].default_value = 1.0
    down.inputs["To Max"].default_value = 0.0
    # (ramp - 1) * has + 1: the ramp where the side is bounded, else 1.
    up_or_one = b.math("MULTIPLY_ADD", b.math("SUBTRACT", up.outputs[0], 1.0, x=0, y=200), gin["Has Min"], 1.0,
                       x=160, y=200)
    down_or_one = b.math("MULTIPLY_ADD", b.math("SUBTRACT", down.outputs[0], 1.0, x=0, y=-200), gin["Has Max"],
                         1.0, x=160, y=-200)
    b.link(b.math("MULTIPLY", up_or_one, down_or_one, x=360, y=0), gout["Weight"])
    return group


def height_blend_group():
    """evaluateLayers()'s height blend for one layer over what lies under it
    (TerrainLayers.h, step 4, for two layers): key = height + share, the
    highest key wins and the other shares within `depth` of it:
    w = share * max(key - (best - depth), 0), normalised. Factor = the
    layer's w over the sum."""
    name = "Strata Height Blend"
    if name in bpy.data.node_groups:
        return bpy.data.node_groups[name]
    group, b, gin, gout = new_group(name, [
        ("NodeSocketFloat", "Coverage"), ("NodeSocketFloat", "Base Height"), ("NodeSocketFloat", "Layer Height"),
        ("NodeSocketFloat", "Depth"),
    ], [("NodeSocketFloat", "Factor")])
    share_base = b.math("SUBTRACT", 1.0, gin["Coverage"], x=-600, y=200)
    key_base = b.math("ADD", gin["Base Height"], share_base, x=-400, y=200)
    key_layer = b.math("ADD", gin["Layer Height"], gin["Coverage"], x=-400, y=-200)
    floor = b.math("SUBTRACT", b.math("MAXIMUM", key_base, key_layer, x=-200, y=0), gin["Depth"], x=0, y=0)
    w_base = b.math("MULTIPLY", share_base,
                    b.math("MAXIMUM", b.math("SUBTRACT", key_base, floor, x=200, y=200), 0.0, x=400, y=200),
                    x=600, y=200)
    w_layer = b.math("MULTIPLY", gin["Coverage"],
                     b.math("MAXIMUM", b.math("SUBTRACT", key_layer, floor, x=200, y=-200), 0.0, x=400, y=-200),
                     x=600, y=-200)
    total = b.math("MAXIMUM", b.math("ADD", w_base, w_layer, x=800, y=0), 1e-20, x=950, y=0)
    b.link(b.math("DIVIDE", w_layer, total, x=1100, y=0), gout["Factor"])
    return group


def group_node(b, group, x, y, **inputs):
    node = b.node("ShaderNodeGroup", x, y)
    node.node_tree = group
    for key, value in inputs.items():
        b.feed(node.inputs[key.replace("_", " ")], value)
    return node.outputs


# ---------------------------------------------------------------------------
# The material


def box_texture(b, image, vector, blend, x, y):
    """One map in Blender's box (triplanar) projection."""
    node = b.node("ShaderNodeTexImage", x, y, projection="BOX", projection_blend=blend,
                  interpolation="Linear", extension="REPEAT")
    node.image = image
    b.link(vector, node.inputs["Vector"])
    return node


def scaled_position(b, position, map_scale, x, y):
    """Texture space: object-space metres times map_scale (repeats per metre)."""
    node = b.node("ShaderNodeMapping", x, y, vector_type="POINT")
    node.inputs["Scale"].default_value = (map_scale, map_scale, map_scale)
    b.link(position, node.inputs["Vector"])
    return node.outputs["Vector"]


def triplanar_normal(b, images, p, n, weights, top, strength, x, y):
    """Strata's normal maps without tangent space, with Blender's box UVs:
    each axis samples the map at the UV the box projection uses there
    (X: (±y, z), Y: (∓x, z), Z: (∓y, x), the sign from the normal's), decodes
    it, and adds its tangent XY along the world axes those UVs follow, times
    the axis's weight (UDN). The Z axis (Strata's top, Y-up) reads the top
    normal map on upward faces."""
    pc = b.separate(p, x, y)
    nc = b.separate(n, x, y - 200)
    sign_x = b.math("SIGN", nc[0], x=x + 160, y=y - 200)
    sign_y = b.math("MULTIPLY", b.math("SIGN", nc[1], x=x + 160, y=y - 320), -1.0, x=x + 320, y=y - 320)
    sign_z = b.math("MULTIPLY", b.math("SIGN", nc[2], x=x + 160, y=y - 440), -1.0, x=x + 320, y=y - 440)

    def sample(image, u_sign, u, v, yy):
        uv = b.combine(b.math("MULTIPLY", u_sign, u, x=x + 480, y=yy), v, 0.0, x=x + 640, y=yy)
        tex = b.node("ShaderNodeTexImage", x + 800, yy, interpolation="Linear", extension="REPEAT")
        tex.image = image
        b.link(uv, tex.inputs["Vector"])
        # decodeNormal(): (c * 2 - 1) * strength on XY
        decoded = b.node("ShaderNodeVectorMath", x + 1080, yy, operation="MULTIPLY_ADD")
        b.link(tex.outputs["Color"], decoded.inputs[0])
        decoded.inputs[1].default_value = (2.0 * strength, 2.0 * strength, 0.0)
        decoded.inputs[2].default_value = (-strength, -strength, 0.0)
        return b.separate(decoded.outputs[0], x + 1240, yy)

    mx = sample(images["normal"], sign_x, pc[1], pc[2], y)
    my = sample(images["normal"], sign_y, pc[0], pc[2], y - 300)
    mz = sample(images["normal"], sign_z, pc[1], pc[0], y - 600)
    if "top_normal" in images:
        mt = sample(images["top_normal"], sign_z, pc[1], pc[0], y - 900)
        mz = [b.lerp(mz[i], mt[i], top, x=x + 1400, y=y - 600 - 120 * i) for i in range(2)]
    # Tangent U follows ±Y, ±X, ±Y and V follows Z, Z, X (the box's UVs):
    # the perturbation in world axes, weighted.
    wx, wy, wz = weights
    ux = b.math("MULTIPLY", b.math("MULTIPLY", mx[0], sign_x, x=x + 1700, y=y), wx, x=x + 1860, y=y)
    vx = b.math("MULTIPLY", mx[1], wx, x=x + 1860, y=y - 120)
    uy = b.math("MULTIPLY", b.math("MULTIPLY", my[0], sign_y, x=x + 1700, y=y - 300), wy, x=x + 1860, y=y - 300)
    vy = b.math("MULTIPLY", my[1], wy, x=x + 1860, y=y - 420)
    uz = b.math("MULTIPLY", b.math("MULTIPLY", mz[0], sign_z, x=x + 1700, y=y - 600), wz, x=x + 1860, y=y - 600)
    vz = b.math("MULTIPLY", mz[1], wz, x=x + 1860, y=y - 720)
    offset = b.combine(b.math("ADD", uy, vz, x=x + 2020, y=y),
                       b.math("ADD", ux, uz, x=x + 2020, y=y - 200),
                       b.math("ADD", vx, vy, x=x + 2020, y=y - 400), x=x + 2180, y=y - 200)
    summed = b.node("ShaderNodeVectorMath", x + 2340, y - 200, operation="ADD")
    b.link(n, summed.inputs[0])
    b.link(offset, summed.inputs[1])
    unit = b.node("ShaderNodeVectorMath", x + 2500, y - 200, operation="NORMALIZE")
    b.link(summed.outputs[0], unit.inputs[0])
    # The coordinates are the object's: back to world space for the BSDF.
    world = b.node("ShaderNodeVectorTransform", x + 2660, y - 200, vector_type="NORMAL",
                   convert_from="OBJECT", convert_to="WORLD")
    b.link(unit.outputs[0], world.inputs[0])
    return world.outputs[0]


# Rule keys read from a vertex attribute (terrain_mesh.py adds them).
ATTRIBUTE_BANDS = {"cavity": "strata_cavity", "cover": "strata_cover", "flow": "strata_flow",
                   "wear": "strata_wear", "deposition": "strata_deposition", "water": "strata_water",
                   "hardness": "strata_hardness", "bed": "strata_bed"}


def band_weight(b, band, value, x, y):
    """One soft band of a rule; the scene gives unbounded sides as infinities."""
    has_min, has_max = math.isfinite(band["min"]), math.isfinite(band["max"])
    return group_node(b, band_group(), x, y, Value=value, Min=band["min"] if has_min else 0.0,
                      Max=band["max"] if has_max else 0.0, Softness=band["softness"],
                      Has_Min=float(has_min), Has_Max=float(has_max))[0]


def noise_value(b, noise, position, x, y):
    """The noise mask's value. Strata's is three octaves of its own value
    noise (layerNoise()); Blender's Noise Texture with two extra octaves at
    the same frequency is the nearest node: the same scale and range, not
    the same pattern."""
    tex = b.node("ShaderNodeTexNoise", x, y, noise_dimensions="3D")
    b.link(position, tex.inputs["Vector"])
    tex.inputs["Scale"].default_value = noise["frequency"]
    tex.inputs["Detail"].default_value = 2.0
    tex.inputs["Roughness"].default_value = 0.5
    return tex.outputs["Fac"]


def layer_coverage(b, rule, position, altitude, slope, x, y):
    """layerCoverage(): opacity times every band of the rule: altitude and
    slope from the geometry, cavity, cover and the landform masks from the
    mesh's attributes, the noise mask from a Noise Texture (approximate)."""
    coverage = rule.get("opacity", 1.0)
    for key, band in rule.items():
        if key in ("opacity", "noise"):
            continue
        if key == "altitude":
            value = altitude
        elif key == "slope":
            value = slope
        elif key in ATTRIBUTE_BANDS:
            value = b.node("ShaderNodeAttribute", x - 200, y, attribute_type="GEOMETRY",
                           attribute_name=ATTRIBUTE_BANDS[key]).outputs["Fac"]
        else:
            continue  # a band this add-on does not know: left at 1
        coverage = b.math("MULTIPLY", band_weight(b, band, value, x, y), coverage, x=x + 200, y=y)
        y -= 200
    if "noise" in rule:
        noise = rule["noise"]
        band = {"min": noise["threshold"], "max": math.inf, "softness": noise["softness"]}
        value = noise_value(b, noise, position, x - 200, y)
        coverage = b.math("MULTIPLY", band_weight(b, band, value, x, y), coverage, x=x + 200, y=y)
    return coverage


def build_material(settings, name):
    """A node material with Strata's look for a strata.MaterialSettings."""
    material = bpy.data.materials.new(f"{name} Strata")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    b = Builder(tree)

    coords = b.node("ShaderNodeTexCoord", -2400, 0)
    position, normal = coords.outputs["Object"], coords.outputs["Normal"]
    blend = box_blend(settings.blend_offset, settings.blend_exponent)
    p = scaled_position(b, position, settings.map_scale, -2200, 0)
    images = material_images(settings, name)

    # Sides and top in box projection.
    side_albedo = box_texture(b, images["albedo"], p, blend, -1900, 600)
    side_mask = box_texture(b, images["mask"], p, blend, -1900, 300) if "mask" in images else None
    n = b.separate(normal, -1900, -300)
    side_height = b.separate(side_mask.outputs["Color"], -1600, 300)[2] if side_mask else 1.0

    # Strata's top maps replace its Y (Blender's Z) projection where the
    # normal points up: the factor is that projection's height-blended weight.
    albedo = side_albedo.outputs["Color"]
    mask_rgb = side_mask.outputs["Color"] if side_mask else (1.0, 1.0, 1.0, 1.0)
    mask_alpha = side_mask.outputs["Alpha"] if side_mask else 1.0
    height = side_height
    up = b.math("GREATER_THAN", n[2], 0.0, x=-1600, y=-300)
    top = 0.0
    strength = settings.height_strength if side_mask else 0.0
    if "top_albedo" in images:
        top_albedo = box_texture(b, images["top_albedo"], p, blend, -1900, 0)
        top_mask = box_texture(b, images["top_mask"], p, blend, -1900, -600) if "top_mask" in images else None
        top_height = b.separate(top_mask.outputs["Color"], -1600, -600)[2] if top_mask else side_height
        z_height = b.lerp(side_height, top_height, up, x=-1400, y=-500)
        weights = group_node(b, weights_group(), -1100, -300, Normal=normal, Offset=settings.blend_offset,
                             Exponent=settings.blend_exponent, Height_X=side_height, Height_Y=side_height,
                             Height_Z=z_height, Height_Strength=strength)
        top = b.math("MULTIPLY", weights[2], up, x=-900, y=-300)
        albedo = b.mix_color(albedo, top_albedo.outputs["Color"], top, x=-700, y=500)
        if top_mask:
            mask_rgb = b.mix_color(mask_rgb, top_mask.outputs["Color"], top, x=-700, y=300)
            mask_alpha = b.lerp(mask_alpha, top_mask.outputs["Alpha"], top, x=-700, y=150)
            height = b.lerp(height, top_height, top, x=-700, y=0)
    else:
        weights = group_node(b, weights_group(), -1100, -300, Normal=normal, Offset=settings.blend_offset,
                             Exponent=settings.blend_exponent, Height_X=side_height, Height_Y=side_height,
                             Height_Z=side_height, Height_Strength=strength)
    albedo = b.mix_color(albedo, tuple(settings.albedo_tint) + (1.0,), 1.0, x=-500, y=500, blend_type="MULTIPLY")

    # [[layer]]s over the base, in painter's order, each height-blended.
    if settings.layers:
        altitude = b.separate(position, -1900, -1200)[2]
        slope = b.math("DEGREES", b.math("ARCCOSINE", b.math("MINIMUM", b.math("MAXIMUM", n[2], -1.0, x=-1900,
                                                                                   y=-1500), 1.0, x=-1750, y=-1500),
                                         x=-1600, y=-1500), x=-1450, y=-1500)
    for index, layer in enumerate(settings.layers):
        y = -1200 - 700 * index
        layer_settings = layer["material"]
        layer_images = material_images(layer_settings, f"{name} {layer.get('name', index + 1)}")
        lp = scaled_position(b, position, layer_settings.map_scale, -1300, y)
        layer_blend = box_blend(layer_settings.blend_offset, layer_settings.blend_exponent)
        layer_albedo = box_texture(b, layer_images["albedo"], lp, layer_blend, -1100, y)
        layer_color = b.mix_color(layer_albedo.outputs["Color"], tuple(layer_settings.albedo_tint) + (1.0,), 1.0,
                                  x=-800, y=y, blend_type="MULTIPLY")
        if "mask" in layer_images:
            layer_mask = box_texture(b, layer_images["mask"], lp, layer_blend, -1100, y - 300)
            layer_rgb, layer_alpha = layer_mask.outputs["Color"], layer_mask.outputs["Alpha"]
            layer_height = b.separate(layer_rgb, -800, y - 300)[2]
        else:
            layer_rgb, layer_alpha, layer_height = (0.0, 1.0, 0.5, 1.0), 0.5, 0.5
        coverage = layer_coverage(b, layer["rule"], position, altitude, slope, -1300, y - 500)
        factor = group_node(b, height_blend_group(), -600, y, Coverage=coverage, Base_Height=height,
                            Layer_Height=layer_height, Depth=settings.layer_blend_depth)[0]
        albedo = b.mix_color(albedo, layer_color, factor, x=-400, y=y)
        mask_rgb = b.mix_color(mask_rgb, layer_rgb, factor, x=-400, y=y - 200)
        mask_alpha = b.lerp(mask_alpha, layer_alpha, factor, x=-400, y=y - 350)
        height = b.lerp(height, layer_height, factor, x=-400, y=y - 500)

    # MOHS: metallic R, occlusion G (on the albedo), smoothness A.
    mask = b.node("ShaderNodeSeparateRGB", 0, 300)
    b.feed(mask.inputs[0], mask_rgb)
    occlusion = b.math("MULTIPLY_ADD", b.math("SUBTRACT", mask.outputs["G"], 1.0, x=200, y=400),
                       settings.occlusion_strength, 1.0, x=360, y=400)
    albedo = b.mix_color(albedo, b.combine(occlusion, occlusion, occlusion, x=520, y=400), 1.0, x=700, y=500,
                         blend_type="MULTIPLY")
    bsdf = b.node("ShaderNodeBsdfPrincipled", 1000, 300)
    b.link(albedo, bsdf.inputs["Base Color"])
    b.feed(bsdf.inputs["Metallic"], b.math("MULTIPLY", mask.outputs["R"], settings.metallic, x=700, y=200,
                                           clamp=True))
    b.feed(bsdf.inputs["Roughness"],
           b.math("SUBTRACT", 1.0, b.math("MULTIPLY", mask_alpha, settings.smoothness, x=600, y=0, clamp=True),
                  x=760, y=0))
    if settings.normal_maps and "normal" in images:
        b.link(triplanar_normal(b, images, p, normal, weights, top, settings.normal_strength, -2200, -2000),
               bsdf.inputs["Normal"])
    out = b.node("ShaderNodeOutputMaterial", 1400, 300)
    b.link(bsdf.outputs["BSDF"], out.inputs["Surface"])
    return material
