// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The height graph's node types (HeightGraph.h, ErodedHeightfield.h) as a
// scene names them.

#include <strata/terrain/CrestHeightfield.h>
#include <strata/terrain/DetailErodedHeightfield.h>
#include <strata/terrain/DifferentialErosion.h>
#include <strata/terrain/ErodedHeightfield.h>
#include <strata/terrain/HeightGraph.h>
#include <strata/terrain/NodeRegistry.h>
#include <strata/terrain/ScreeField.h>
#include <strata/terrain/TalusHeightfield.h>

#include "NodeRegistrations.h"

#include <strata/Format.h>

namespace strata::terrain {

HeightNodePtr heightChild(const NodeArgs& args, const std::string& key)
{
    const DensityFieldPtr child = args.child(key);
    if (!child) return nullptr;
    HeightNodePtr height = std::dynamic_pointer_cast<const HeightfieldBase>(child);
    if (!height) {
        args.fail(key, "must name a height node (heightfield, image_heightfield, erode, height_* or mask_*), "
                       "not a 3D node");
    }
    return height;
}

namespace {

std::vector<HeightNodePtr> heightChildren(const NodeArgs& args, const std::string& key)
{
    std::vector<HeightNodePtr> out;
    for (const DensityFieldPtr& child : args.children(key)) {
        HeightNodePtr height = std::dynamic_pointer_cast<const HeightfieldBase>(child);
        if (!height) args.fail(key, "must name height nodes only (heightfield, erode, height_*, mask_*), not 3D nodes");
        out.push_back(std::move(height));
    }
    return out;
}

void addCombine(NodeRegistry& registry, const char* name, HeightOp op, const char* description)
{
    NodeType t{name, description, {}, {}};
    t.keys = {childrenKey("children", "the height nodes, folded left to right")};
    t.build = [op](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<HeightCombine>(op, heightChildren(a, "children"));
    };
    registry.add(std::move(t));
}

void addMask(NodeRegistry& registry, const char* name, MaskSource source, const char* description, const char* unit,
             double min, double max, double softness)
{
    NodeType t{name, description, {}, {}};
    t.keys = {childKey("child", "the height node measured"),
              numberKey("min", min, -1e9, 1e9, unit, "lower end of the band where the mask is 1"),
              numberKey("max", max, -1e9, 1e9, unit, "upper end of the band where the mask is 1"),
              numberKey("softness", softness, 1e-9, 1e9, unit, "the mask falls to 0 over this much outside the band")};
    if (source != MaskSource::Height) {
        t.keys.push_back(numberKey("radius", 4.0, 1e-3, MAX_LENGTH, "m", "step of the finite differences (smooths)"));
    }
    t.build = [source](const NodeArgs& a) -> DensityFieldPtr {
        MaskOptions o;
        o.source = source;
        o.min = a.number("min");
        o.max = a.number("max");
        if (o.max < o.min) a.fail("max", "must be >= min (" + formatNumber(o.min) + ")");
        o.softness = a.number("softness");
        if (source != MaskSource::Height) o.radius = a.number("radius");
        return std::make_shared<HeightMask>(heightChild(a, "child"), o);
    };
    registry.add(std::move(t));
}

/// height_constant and the nodes that combine heights: add, subtract, multiply, min, max, blend.
void registerArithmeticNodes(NodeRegistry& registry)
{
    NodeType constant{"height_constant", "h = value: a flat height", {}, {}};
    constant.keys = {numberKey("value", 0.0, -HUGE_LENGTH, HUGE_LENGTH, "m", "the height")};
    constant.build = [](const NodeArgs& a) -> DensityFieldPtr { return std::make_shared<ConstantHeight>(a.number("value")); };
    registry.add(std::move(constant));

    addCombine(registry, "height_add", HeightOp::Add, "h = a + b + ...: sums height nodes");
    addCombine(registry, "height_subtract", HeightOp::Subtract, "h = a - b - ...: the first minus the rest");
    addCombine(registry, "height_multiply", HeightOp::Multiply, "h = a * b * ...: e.g. a height times a mask");
    addCombine(registry, "height_min", HeightOp::Min, "h = min(a, b, ...): the lowest");
    addCombine(registry, "height_max", HeightOp::Max, "h = max(a, b, ...): the highest");

    NodeType blend{"height_blend", "h = a + mask * (b - a): b where the mask is 1, a where it is 0", {}, {}};
    blend.keys = {childKey("a", "height where the mask is 0"), childKey("b", "height where the mask is 1"),
                  childKey("mask", "height node read as 0..1 (clamped), e.g. a mask_* node")};
    blend.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<HeightBlend>(heightChild(a, "a"), heightChild(a, "b"), heightChild(a, "mask"));
    };
    registry.add(std::move(blend));
}

/// The nodes that reshape one height: curve, scale, clamp, warp, terrace.
void registerShapingNodes(NodeRegistry& registry)
{
    NodeType curve{"height_curve", "h = curve(child): remaps heights through points (monotone cubic, no overshoot)",
                   {}, {}};
    curve.keys = {childKey("child", "the height node remapped"),
                  pointsKey("points", {{0.0, 0.0}, {1.0, 1.0}}, HUGE_LENGTH, "m",
                            "[input, output] pairs, inputs increasing; flat beyond the ends")};
    curve.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<HeightCurve>(heightChild(a, "child"), a.points("points"));
    };
    registry.add(std::move(curve));

    NodeType scale{"height_scale", "h = child * scale + offset", {}, {}};
    scale.keys = {childKey("child", "the height node scaled"),
                  numberKey("scale", 1.0, -1e6, 1e6, "", "factor (negative flips)"),
                  numberKey("offset", 0.0, -HUGE_LENGTH, HUGE_LENGTH, "m", "added after scaling")};
    scale.build = [](const NodeArgs& a) -> DensityFieldPtr {
        HeightAffineOptions o;
        o.scale = a.number("scale");
        o.offset = a.number("offset");
        return std::make_shared<HeightAffine>(heightChild(a, "child"), o);
    };
    registry.add(std::move(scale));

    NodeType clamp{"height_clamp", "h = clamp(child, min, max): plateaus and flat floors", {}, {}};
    clamp.keys = {childKey("child", "the height node clamped"),
                  numberKey("min", -HUGE_LENGTH, -HUGE_LENGTH, HUGE_LENGTH, "m", "lowest height"),
                  numberKey("max", HUGE_LENGTH, -HUGE_LENGTH, HUGE_LENGTH, "m", "highest height")};
    clamp.build = [](const NodeArgs& a) -> DensityFieldPtr {
        HeightAffineOptions o;
        o.min = a.number("min");
        o.max = a.number("max");
        if (o.max < o.min) a.fail("max", "must be >= min");
        return std::make_shared<HeightAffine>(heightChild(a, "child"), o);
    };
    registry.add(std::move(clamp));

    const HeightWarpOptions w;
    NodeType warp{"height_warp", "h = child(p + amplitude * noise2(p / wavelength)): 2D domain warp", {}, {}};
    warp.keys = {childKey("child", "the height node warped"),
                 numberKey("amplitude", w.amplitude, 0.0, MAX_LENGTH, "m", "how far points move"),
                 numberKey("wavelength", w.wavelength, 1e-3, MAX_LENGTH, "m", "size of the warp's features")};
    addFractalKeys(warp.keys, w.noise);
    warp.build = [](const NodeArgs& a) -> DensityFieldPtr {
        HeightWarpOptions o;
        o.amplitude = a.number("amplitude");
        o.wavelength = a.number("wavelength");
        o.noise = fractalOptions(a);
        return std::make_shared<HeightWarp>(heightChild(a, "child"), a.seed(), o);
    };
    registry.add(std::move(warp));

    NodeType terrace{"height_terrace", "heights cut into steps (the terrace profile on h)", {}, {}};
    terrace.keys = {childKey("child", "the height node terraced"),
                    numberKey("step", 10.0, 1e-6, MAX_LENGTH, "m", "height of one step"),
                    numberKey("sharpness", 4.0, 1.0, 64.0, "", "1 = no terraces, larger = flatter treads")};
    terrace.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<HeightTerrace>(heightChild(a, "child"), a.number("step"), a.number("sharpness"));
    };
    registry.add(std::move(terrace));
}

/// The masks: 1 where a height, slope or curvature is within a band.
void registerMaskNodes(NodeRegistry& registry)
{
    addMask(registry, "mask_height", MaskSource::Height, "1 where the child's height is within [min, max], else 0",
            "m", 0.0, 100.0, 10.0);
    addMask(registry, "mask_slope", MaskSource::Slope, "1 where the child's slope (rise/run) is within [min, max]",
            "", 0.0, 0.5, 0.1);
    addMask(registry, "mask_curvature", MaskSource::Curvature,
            "1 where the child's curvature -laplacian(h) is within [min, max] (> 0 ridges, < 0 valleys)", "1/m",
            0.0, 1.0, 0.01);
}

/// erode: landscape evolution over a fixed domain (ErodedHeightfield.h).
void registerErodeNode(NodeRegistry& registry)
{
    const ErodeOptions e;
    NodeType erode{"erode",
                   "landscape evolution of a height node over a fixed domain: uplift, stream-power rivers with lakes, "
                   "hillslope creep; leaves flow, wear, deposition and water masks",
                   {}, {}};
    erode.keys = {
        childKey("height", "the height node eroded (the initial surface)"),
        optionalChildKey("uplift_map", "height node scaling the uplift per place (e.g. 0..1); none: uniform"),
        vec2Key("min", e.min, HUGE_LENGTH, "m", "world (x, z) of the domain's first corner"),
        vec2Key("max", e.max, HUGE_LENGTH, "m", "world (x, z) of the domain's far corner"),
        numberKey("cell_size", e.evolution.cellSize, 1e-3, 1e6, "m", "grid spacing of the evolution"),
        numberKey("years", e.evolution.years, 0.0, 1e10, "yr", "time simulated"),
        numberKey("time_step", e.evolution.timeStep, 1e-3, 1e10, "yr", "years per implicit step"),
        numberKey("uplift", e.evolution.uplift, -1.0, 1.0, "m/yr", "rock uplift rate U"),
        numberKey("erodibility", e.evolution.erodibility, 0.0, 1.0, "m^(1-2m)/yr", "stream-power constant K"),
        numberKey("m", e.evolution.areaExponent, 0.0, 2.0, "", "drainage-area exponent"),
        numberKey("n", e.evolution.slopeExponent, 0.01, 4.0, "", "slope exponent"),
        numberKey("diffusivity", e.evolution.diffusivity, 0.0, 1e4, "m^2/yr", "hillslope creep D"),
        numberKey("river_area", e.riverArea, 1e-6, 1e15, "m^2", "drainage area where the water mask starts"),
    };
    erode.build = [](const NodeArgs& a) -> DensityFieldPtr {
        ErodeOptions o;
        o.min = a.vec2("min");
        o.max = a.vec2("max");
        o.evolution.cellSize = a.number("cell_size");
        o.evolution.years = a.number("years");
        o.evolution.timeStep = a.number("time_step");
        o.evolution.uplift = a.number("uplift");
        o.evolution.erodibility = a.number("erodibility");
        o.evolution.areaExponent = a.number("m");
        o.evolution.slopeExponent = a.number("n");
        o.evolution.diffusivity = a.number("diffusivity");
        o.riverArea = a.number("river_area");
        // Refused before any work when the pass would not fit the budget.
        const std::uint64_t budget = a.context().maxMemoryBytes;
        // (A domain over MAX_CELLS is refused by the node itself, naming cell_size.)
        const std::size_t cells = ErodedHeightfield::cellCount(o);
        if (budget > 0 && cells <= ErodedHeightfield::MAX_CELLS && ErodedHeightfield::peakBytes(o) > budget) {
            a.fail("cell_size", "= " + formatNumber(o.evolution.cellSize) + ": the erosion pass over " +
                                    std::to_string(cells) + " cells needs about " +
                                    std::to_string(ErodedHeightfield::peakBytes(o) >> 20) +
                                    " MiB, over the memory budget of " + std::to_string(budget >> 20) +
                                    " MiB (--max-memory): use a larger cell_size or a smaller domain");
        }
        return std::make_shared<ErodedHeightfield>(heightChild(a, "height"), heightChild(a, "uplift_map"), o,
                                                   a.context().progress);
    };
    registry.add(std::move(erode));
}

/// erode_detail: voxel-scale droplet and talus erosion in fixed world blocks
/// (DetailErodedHeightfield.h).
void registerDetailErodeNode(NodeRegistry& registry)
{
    const DetailErodeOptions d;
    const DetailErosionOptions& de = d.erosion;
    NodeType detail{"erode_detail",
                    "voxel-scale erosion over a height node: water droplets carve rills and drop sediment, steep "
                    "slopes slide to the talus angle; computed in fixed world blocks, the same for any tiling",
                    {}, {}};
    detail.keys = {
        childKey("height", "the height node detailed"),
        numberKey("cell_size", de.cellSize, 1e-3, 1e4, "m", "spacing of the droplet grid (the voxel size suits)"),
        numberKey("droplets_per_cell", de.dropletsPerCell, 0.0, 8.0, "", "droplets started per cell"),
        integerKey("droplet_steps", de.dropletSteps, 1, 256, "cells", "how far a droplet may run"),
        numberKey("inertia", de.inertia, 0.0, 1.0, "", "how much a droplet keeps its direction"),
        numberKey("capacity", de.capacity, 0.0, 1e3, "", "sediment carried per unit of drop, speed and water"),
        numberKey("erosion", de.erosion, 0.0, 1.0, "", "fraction of spare capacity picked up per step"),
        numberKey("deposition", de.deposition, 0.0, 1.0, "", "fraction of excess sediment dropped per step"),
        numberKey("evaporation", de.evaporation, 0.0, 1.0, "", "fraction of water lost per step"),
        numberKey("talus_angle", de.talusAngle, 1.0, 89.0, "deg", "slopes steeper than this slide (thermal erosion)"),
        integerKey("talus_sweeps", de.talusSweeps, 0, 256, "", "relaxation sweeps of the talus slide"),
        numberKey("max_depth", de.maxDepth, 1e-3, 1e3, "m", "largest change, up or down"),
        integerKey("block", d.blockCells, 8, 1024, "cells", "side of the fixed world blocks"),
        integerKey("halo", 0, 0, 512, "cells", "reach beyond a block (0: droplet_steps, at most block / 2)"),
        seedKey(),
    };
    detail.build = [](const NodeArgs& a) -> DensityFieldPtr {
        DetailErodeOptions o;
        DetailErosionOptions& e = o.erosion;
        e.cellSize = a.number("cell_size");
        e.dropletsPerCell = a.number("droplets_per_cell");
        e.dropletSteps = int(a.integer("droplet_steps"));
        e.inertia = a.number("inertia");
        e.capacity = a.number("capacity");
        e.erosion = a.number("erosion");
        e.deposition = a.number("deposition");
        e.evaporation = a.number("evaporation");
        e.talusAngle = a.number("talus_angle");
        e.talusSweeps = int(a.integer("talus_sweeps"));
        e.maxDepth = a.number("max_depth");
        o.blockCells = int(a.integer("block"));
        o.halo = int(a.integer("halo"));
        return std::make_shared<DetailErodedHeightfield>(heightChild(a, "height"), a.seed(), o);
    };
    registry.add(std::move(detail));
}

/// talus (scree cones on a height node) and scree (the cones laid over 3D rock).
void registerTalusNodes(NodeRegistry& registry)
{
    const TalusOptions t;
    NodeType talus{"talus",
                   "scree cones and aprons at the foot of steep faces, at the angle of repose: debris from a "
                   "fraction of each face's height, never steeper than `angle`; the thickness is a landform mask "
                   "(deposition)",
                   {}, {}};
    talus.keys = {
        childKey("height", "the ground the talus is shed onto"),
        numberKey("angle", t.angle, 5.0, 60.0, "deg", "angle of repose: the steepest the talus lies"),
        numberKey("fill", t.fill, 0.0, 1.0, "", "fraction of a face's height above its foot the talus may bury"),
        numberKey("max_height", t.maxHeight, 1e-3, 1e4, "m", "the tallest cone above the foot of its face"),
        numberKey("cell_size", t.cellSize, 1e-3, 1e4, "m", "spacing of the lattice the cones are computed on"),
        integerKey("block", t.blockCells, 16, 1024, "cells", "side of the fixed world blocks"),
    };
    talus.build = [](const NodeArgs& a) -> DensityFieldPtr {
        TalusOptions o;
        o.angle = a.number("angle");
        o.fill = a.number("fill");
        o.maxHeight = a.number("max_height");
        o.cellSize = a.number("cell_size");
        o.blockCells = int(a.integer("block"));
        return std::make_shared<TalusHeightfield>(heightChild(a, "height"), o);
    };
    registry.add(std::move(talus));

    NodeType scree{"scree",
                   "a `talus` node's cones laid over 3D rock (after beds or warps cut it): they fill the foot of "
                   "the walls and the alcoves there, never steeper than the talus angle",
                   {}, {}};
    scree.keys = {
        childKey("child", "the rock (a 3D node)"),
        childKey("talus", "a `talus` node over the ground the rock was cut from"),
        numberKey("depth", 2.0, 1e-3, 1e4, "m", "how far below the foot of the walls the talus reaches"),
    };
    scree.build = [](const NodeArgs& a) -> DensityFieldPtr {
        auto talus = std::dynamic_pointer_cast<const TalusHeightfield>(a.child("talus"));
        if (!talus) a.fail("talus", "must name a `talus` node");
        return std::make_shared<ScreeField>(a.child("child"), talus, a.number("depth"));
    };
    registry.add(std::move(scree));
}

/// crests: rounded ridges sharpened to the edge where their flanks meet.
void registerCrestNode(NodeRegistry& registry)
{
    const CrestOptions c;
    NodeType crests{"crests",
                    "sharp crests where a height node's ridges came out rounded (an erode grid's spline rounds them "
                    "over about two cells): both flanks extended to where they meet, only upward; planes and valleys "
                    "stay as they are, soft rock stays rounded when `beds` is given",
                    {}, {}};
    crests.keys = {
        childKey("height", "the height node whose ridges are sharpened, e.g. an erode node"),
        numberKey("reach", c.reach, 1e-3, 1e6, "m",
                  "how far out the flanks are read (and twice that): more than the rounding's half width"),
        numberKey("amount", c.amount, 0.0, 1.0, "", "share of the way up to where the flanks meet"),
        numberKey("max_lift", c.maxLift, 0.0, 1e4, "m", "the most a crest is raised"),
        optionalChildKey("mask", "a height node read as 0..1 (clamped) that scales the lift, e.g. a mask_* node"),
        optionalChildKey("beds", "a `beds` node: the lift is scaled by the hardness of its rock at the ground"),
    };
    crests.build = [](const NodeArgs& a) -> DensityFieldPtr {
        CrestOptions o;
        o.reach = a.number("reach");
        o.amount = a.number("amount");
        o.maxLift = a.number("max_lift");
        std::shared_ptr<const Lithology> lithology;
        if (const DensityFieldPtr beds = a.child("beds")) {
            const auto field = std::dynamic_pointer_cast<const DifferentialErosionField>(beds);
            if (!field) a.fail("beds", "must name a `beds` node");
            lithology = field->lithologyPtr();
        }
        return std::make_shared<CrestHeightfield>(heightChild(a, "height"), o, heightChild(a, "mask"), lithology);
    };
    registry.add(std::move(crests));
}

} // namespace

void registerHeightGraphNodes(NodeRegistry& registry)
{
    registerArithmeticNodes(registry);
    registerShapingNodes(registry);
    registerMaskNodes(registry);
    registerErodeNode(registry);
    registerDetailErodeNode(registry);
    registerTalusNodes(registry);
    registerCrestNode(registry);
}

} // namespace strata::terrain
