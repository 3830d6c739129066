// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/CpuRenderer.h>

#include "AtmosphereSetup.h"
#include "LayerSetup.h"
#include "MaterialMaps.h"
#include "ShadingBridge.h"
#include "ShadowSetup.h"

#include <strata/Error.h>

#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace strata::render {

namespace {

constexpr int TILE = 32;         // pixels, even (quads never straddle tiles)
constexpr int SUBPIXEL_BITS = 8; // vertices snap to 1/256 pixel
constexpr float SUBPIXEL = float(1 << SUBPIXEL_BITS);
constexpr float GUARD = 4.0f; // guard band, in multiples of the viewport half-size
constexpr int MAX_SAMPLES = 16;

/// Where a pixel's coverage samples lie: 1/256-pixel offsets from its
/// top-left corner in image space (y down). The standard patterns of D3D
/// and Vulkan, as GL drivers report them through glGetMultisamplefv
/// (GL_SAMPLE_POSITION, window coordinates, y up: llvmpipe's 4× pattern is
/// checked against the driver's in tests/render/CpuMsaaTest.cpp; the same
/// numbers read y down give a mirrored pattern, which measured 39.4 dB
/// instead of 54.0 dB against llvmpipe on the default scene). A count
/// without a pattern takes the next lower one.
struct SamplePattern
{
    int count = 1;
    std::array<std::array<int, 2>, MAX_SAMPLES> offset{};
};

SamplePattern samplePattern(int samples)
{
    // Sixteenths of a pixel, GL window coordinates (y up).
    static constexpr int P1[1][2] = {{8, 8}};
    static constexpr int P2[2][2] = {{12, 12}, {4, 4}};
    static constexpr int P4[4][2] = {{6, 2}, {14, 6}, {2, 10}, {10, 14}};
    static constexpr int P8[8][2] = {{9, 5}, {7, 11}, {13, 9}, {5, 3}, {3, 13}, {1, 7}, {11, 15}, {15, 1}};
    static constexpr int P16[16][2] = {{9, 9}, {7, 5}, {5, 10}, {12, 7}, {3, 6},  {10, 13}, {13, 11}, {11, 3},
                                       {6, 14}, {8, 1}, {4, 2}, {2, 12}, {0, 8}, {15, 4},  {14, 15}, {1, 0}};
    SamplePattern pattern;
    auto take = [&](const int (*table)[2], int count) {
        pattern.count = count;
        for (int i = 0; i < count; ++i) pattern.offset[std::size_t(i)] = {table[i][0] * 16, 256 - table[i][1] * 16};
    };
    if (samples >= 16) take(P16, 16);
    else if (samples >= 8) take(P8, 8);
    else if (samples >= 4) take(P4, 4);
    else if (samples >= 2) take(P2, 2);
    else take(P1, 1);
    return pattern;
}

/// The CPU side of SAMPLE_MAP: filtered sampling of the nine slots of the
/// selected layer (STRATA_SELECT_LAYER). Each tile shades with its own
/// copy, which counts its fetches (CpuRenderStats).
struct CpuMaps
{
    std::array<std::array<const Texture*, 9>, STRATA_MAX_LAYERS> layers{};
    mutable int layer = 0;
    mutable std::uint32_t features = 0;
    TextureFilter filter = TextureFilter::Trilinear;
    LodLog2 lodLog2 = LodLog2::Exact;
    mutable std::uint64_t fetches = 0; ///< SAMPLE_MAP calls
    /// Per layer, a bit per map slot sampled at the current fragment.
    mutable std::array<std::uint16_t, STRATA_MAX_LAYERS> sampled{};
    /// A bit per layer sampled with anti-tiling (three taps a lookup).
    mutable std::uint32_t antiTiled = 0;

    glm::vec4 sample(int map, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy) const
    {
        ++fetches;
        sampled[std::size_t(layer)] |= std::uint16_t(1u << map);
        if ((features & feature::ANTI_TILING) != 0u) antiTiled |= 1u << layer;
        return sampleFiltered(*layers[std::size_t(layer)][std::size_t(map)], filter, uv, dUVdx, dUVdy, lodLog2);
    }

    void select(int index, std::uint32_t layerFeatures) const
    {
        layer = index;
        features = layerFeatures;
    }
};

struct ClipVertex
{
    glm::vec4 clip;
    glm::vec3 position; // relative to the mesh origin
    glm::vec3 normal;
    glm::vec2 surface;  // cavity, cover
    glm::vec4 landform; // flow, wear, deposition, water
    glm::vec2 rock;     // hardness, bed
};

/// A screen-space triangle ready for rasterization (image space, y down).
struct Triangle
{
    std::int64_t x[3], y[3]; // fixed point, SUBPIXEL_BITS
    float sx[3], sy[3];      // the same, as float pixels
    float invW[3];
    float z[3]; // window depth 0.5·z_ndc + 0.5, as GL interpolates it
    glm::vec3 position[3];
    glm::vec3 normal[3];
    glm::vec2 surface[3];
    glm::vec4 landform[3];
    glm::vec2 rock[3];
    float area2;                // twice the signed area in float pixels, > 0
    int minX, minY, maxX, maxY; // pixel bounds (inclusive), clamped to the image
};

ClipVertex lerpVertex(const ClipVertex& a, const ClipVertex& b, float t)
{
    return {a.clip + (b.clip - a.clip) * t, a.position + (b.position - a.position) * t,
            a.normal + (b.normal - a.normal) * t, a.surface + (b.surface - a.surface) * t,
            a.landform + (b.landform - a.landform) * t, a.rock + (b.rock - a.rock) * t};
}

/// Sutherland–Hodgman against one homogeneous plane dot(plane, clip) >= 0.
int clipPolygon(const ClipVertex* in, int count, ClipVertex* out, const glm::vec4& plane)
{
    int n = 0;
    for (int i = 0; i < count; ++i) {
        const ClipVertex& a = in[i];
        const ClipVertex& b = in[(i + 1) % count];
        const float da = glm::dot(plane, a.clip);
        const float db = glm::dot(plane, b.clip);
        if (da >= 0.0f) out[n++] = a;
        if ((da >= 0.0f) != (db >= 0.0f)) out[n++] = lerpVertex(a, b, da / (da - db));
    }
    return n;
}

/// Edge function of a→b at p, in fixed point (exact in 64 bits).
inline std::int64_t edge(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t px,
                         std::int64_t py)
{
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

/// Top-left rule in image space (y down), for an edge whose interior is on
/// the side where edge() > 0: the inward normal is (−dy, dx); a left edge
/// has it pointing to +x, a top edge (horizontal) to +y.
inline bool isTopLeft(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by)
{
    const std::int64_t nx = -(by - ay);
    const std::int64_t ny = bx - ax;
    return nx > 0 || (nx == 0 && ny > 0);
}

struct Interpolated
{
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 surface;
    glm::vec4 landform;
    glm::vec2 rock;
    bool valid;
};

/// Perspective-correct attributes of triangle `t` at pixel centre (px, py)
/// (float pixels, image space); also outside the triangle (helper pixels).
Interpolated interpolate(const Triangle& t, float px, float py)
{
    const float l0 = ((t.sx[2] - t.sx[1]) * (py - t.sy[1]) - (t.sy[2] - t.sy[1]) * (px - t.sx[1])) / t.area2;
    const float l1 = ((t.sx[0] - t.sx[2]) * (py - t.sy[2]) - (t.sy[0] - t.sy[2]) * (px - t.sx[2])) / t.area2;
    const float l2 = 1.0f - l0 - l1;
    const float q0 = l0 * t.invW[0];
    const float q1 = l1 * t.invW[1];
    const float q2 = l2 * t.invW[2];
    const float sum = q0 + q1 + q2;
    if (!(sum > 1e-20f)) {
        return {{}, {}, {}, {}, {}, false};
    }
    const float inv = 1.0f / sum;
    return {(t.position[0] * q0 + t.position[1] * q1 + t.position[2] * q2) * inv,
            (t.normal[0] * q0 + t.normal[1] * q1 + t.normal[2] * q2) * inv,
            (t.surface[0] * q0 + t.surface[1] * q1 + t.surface[2] * q2) * inv,
            (t.landform[0] * q0 + t.landform[1] * q1 + t.landform[2] * q2) * inv,
            (t.rock[0] * q0 + t.rock[1] * q1 + t.rock[2] * q2) * inv, true};
}

struct Frame
{
    int width, height;
    float mapScale;
    glm::vec3 textureOffset;
    glm::vec3 detailOffset;   // fract(floor(origin · mapScale) · detailScale), as GlRenderer.cpp
    glm::vec3 tileOffset;     // floor(origin · mapScale) modulo 256
    glm::vec3 cameraPosition; // relative to the mesh origin
    shading::MaterialParams material;
    shading::LayerSetParams layerSet; // layered materials (feature::LAYERS)
    shading::LightingParams lighting;
    shading::AtmosphereParams atmosphere;
    CpuMaps maps;
};

/// One fragment's inputs: `s` in texture space, `world` the same in metres
/// relative to the mesh origin (the layers map it themselves).
struct Fragment
{
    shading::SurfaceInput s;
    shading::SurfaceInput world;
    glm::vec2 surface;
    glm::vec4 landform;
    glm::vec2 rock;
};

using ShadeFunction = glm::vec3 (*)(const Frame&, const CpuMaps&, const Fragment&, const shading::LightingParams&);

/// terrain.frag's material: the base alone, or every layer (TerrainLayers.h).
template <unsigned FEATURES>
shading::SurfaceOutput evaluateWith(const Frame& frame, const CpuMaps& maps, const Fragment& f)
{
    if constexpr ((FEATURES & feature::LAYERS) != 0u) {
        if ((maps.features & feature::LAYERS) != 0u) {
            return shading::evaluateLayers<FEATURES, CpuMaps>(maps, frame.layerSet, f.world, f.surface, f.landform,
                                                                     f.rock);
        }
    }
    return shading::evaluateSurface<FEATURES, CpuMaps>(maps, f.s, frame.material);
}

/// terrain.frag's shaded path: the material, lit, through the atmosphere,
/// tone mapped.
template <unsigned FEATURES>
glm::vec3 shadeWith(const Frame& frame, const CpuMaps& maps, const Fragment& f, const shading::LightingParams& lighting)
{
    const std::uint32_t selected = maps.features;
    const shading::SurfaceOutput o = evaluateWith<FEATURES>(frame, maps, f);
    maps.features = selected; // the layers select their own sets
    const glm::vec3 radiance = shading::lightSurface(o, f.s.viewDir, lighting, o.fresnelStrength);
    return shading::finishFragment(radiance, lighting.exposure, frame.atmosphere, frame.cameraPosition,
                                   f.world.p);
}

/// The CPU side of SHADOW_FETCH: a square depth map, stored rows top to
/// bottom as the rasterizer writes them, read in GL's texel order (y = 0 the
/// bottom row).
struct CpuShadowMap
{
    std::vector<float> texels;
    int resolution = 0;

    float depth(int x, int y) const
    {
        return texels[std::size_t(resolution - 1 - y) * std::size_t(resolution) + std::size_t(x)];
    }
};

/// Exact instantiations for common feature sets (every test folds to a
/// constant); anything else runs the all-features instantiation, which
/// tests the material's bits at run time.
ShadeFunction shadeFunctionFor(std::uint32_t features)
{
    switch (features) {
    case 0:
        return &shadeWith<0u>;
    case feature::MASK_MAP | feature::HEIGHT_BLEND:
        return &shadeWith<feature::MASK_MAP | feature::HEIGHT_BLEND>;
    case feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP:
        return &shadeWith<feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP>;
    case feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP | feature::TOP_MAPS:
        return &shadeWith<feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP | feature::TOP_MAPS>;
    case feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP | feature::TOP_MAPS | feature::DETAIL:
        return &shadeWith<feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP | feature::TOP_MAPS |
                          feature::DETAIL>;
    default:
        return &shadeWith<feature::ALL>;
    }
}

std::uint8_t encode(float linearDisplay)
{
    const float c = shading::linearToSrgb(std::clamp(linearDisplay, 0.0f, 1.0f));
    return std::uint8_t(std::lround(c * 255.0f));
}

/// Clips, projects, snaps and culls the mesh's triangles for a
/// width × height viewport, `clip` being the vertices in clip space. With
/// `cullBackFaces` false both windings are kept (the shadow pass). Each
/// input triangle gives at most 7 (clipping by 6 planes); collected per
/// chunk, in input order.
std::vector<Triangle> setupTriangles(const MeshView& mesh, const std::vector<glm::vec4>& clip, int width, int height,
                                     bool cullBackFaces, bool anySamplePosition = false)
{
    const std::size_t triangleCount = mesh.indexCount / 3;
    const glm::vec4 planes[6] = {{0, 0, 1, 1},     {0, 0, -1, 1},     {-1, 0, 0, GUARD},
                                 {1, 0, 0, GUARD}, {0, -1, 0, GUARD}, {0, 1, 0, GUARD}};
    constexpr std::size_t CHUNK = 4096;
    const std::size_t chunkCount = (triangleCount + CHUNK - 1) / CHUNK;
    std::vector<std::vector<Triangle>> chunks(chunkCount);
    tbb::parallel_for(std::size_t(0), chunkCount, [&](std::size_t c) {
        std::vector<Triangle>& out = chunks[c];
        const std::size_t end = std::min(triangleCount, (c + 1) * CHUNK);
        for (std::size_t t = c * CHUNK; t < end; ++t) {
            ClipVertex polygon[2][9];
            int count = 3;
            bool inside = true;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t index = mesh.indices[t * 3 + std::size_t(k)];
                polygon[0][k] = {clip[index], mesh.positions[index], mesh.normals[index],
                                 mesh.surface ? mesh.surface[index] : glm::vec2(0.0f),
                                 mesh.landform ? mesh.landform[index] : glm::vec4(0.0f),
                                 mesh.rock ? mesh.rock[index] : glm::vec2(0.0f)};
                for (const glm::vec4& plane : planes) {
                    inside = inside && glm::dot(plane, clip[index]) >= 0.0f;
                }
            }
            int current = 0;
            if (!inside) {
                for (const glm::vec4& plane : planes) {
                    count = clipPolygon(polygon[current], count, polygon[1 - current], plane);
                    current = 1 - current;
                    if (count < 3) break;
                }
            }
            if (count < 3) continue;
            // Project and snap.
            std::int64_t fx[9], fy[9];
            float invW[9], z[9];
            for (int k = 0; k < count; ++k) {
                const glm::vec4& v = polygon[current][k].clip;
                const float iw = 1.0f / v.w;
                const float ndcX = v.x * iw;
                const float ndcY = v.y * iw;
                // GL window coordinates (y up), then image space (y down).
                const float wx = (ndcX * 0.5f + 0.5f) * float(width);
                const float wy = (ndcY * 0.5f + 0.5f) * float(height);
                fx[k] = std::llround(double(wx) * SUBPIXEL);
                fy[k] = std::llround(double(float(height) - wy) * SUBPIXEL);
                invW[k] = iw;
                z[k] = (v.z * iw) * 0.5f + 0.5f;
            }
            for (int k = 1; k + 1 < count; ++k) {
                const int ids[3] = {0, k, k + 1};
                // In image space (y down) a GL front face (CCW, y up) is clockwise: edge(0,1,2) < 0.
                const std::int64_t area = edge(fx[ids[0]], fy[ids[0]], fx[ids[1]], fy[ids[1]], fx[ids[2]], fy[ids[2]]);
                if (area == 0 || (area > 0 && cullBackFaces)) continue; // degenerate or back-facing
                Triangle tri;
                // Reorder to a positive area: 0, 2, 1 for front faces.
                const int front[3] = {ids[0], ids[2], ids[1]};
                const int* order = area < 0 ? front : ids;
                for (int m = 0; m < 3; ++m) {
                    const int o = order[m];
                    tri.x[m] = fx[o];
                    tri.y[m] = fy[o];
                    tri.sx[m] = float(fx[o]) / SUBPIXEL;
                    tri.sy[m] = float(fy[o]) / SUBPIXEL;
                    tri.invW[m] = invW[o];
                    tri.z[m] = z[o];
                    tri.position[m] = polygon[current][o].position;
                    tri.normal[m] = polygon[current][o].normal;
                    tri.surface[m] = polygon[current][o].surface;
                    tri.landform[m] = polygon[current][o].landform;
                    tri.rock[m] = polygon[current][o].rock;
                }
                tri.area2 = float(area < 0 ? -area : area) / (SUBPIXEL * SUBPIXEL);
                const std::int64_t half = 1 << (SUBPIXEL_BITS - 1);
                auto lo = [&](const std::int64_t* v) { return std::min({v[0], v[1], v[2]}); };
                auto hi = [&](const std::int64_t* v) { return std::max({v[0], v[1], v[2]}); };
                // Pixel centres (i·256 + 128) inside [lo, hi]; with several
                // samples, every pixel the bounds touch.
                const std::int64_t first = anySamplePosition ? 0 : half;
                const std::int64_t last = anySamplePosition ? (1 << SUBPIXEL_BITS) - 1 : half;
                tri.minX =
                    int(std::max<std::int64_t>(0, (lo(tri.x) - last + (1 << SUBPIXEL_BITS) - 1) >> SUBPIXEL_BITS));
                tri.minY =
                    int(std::max<std::int64_t>(0, (lo(tri.y) - last + (1 << SUBPIXEL_BITS) - 1) >> SUBPIXEL_BITS));
                tri.maxX = int(std::min<std::int64_t>(width - 1, (hi(tri.x) - first) >> SUBPIXEL_BITS));
                tri.maxY = int(std::min<std::int64_t>(height - 1, (hi(tri.y) - first) >> SUBPIXEL_BITS));
                if (tri.minX > tri.maxX || tri.minY > tri.maxY) continue;
                out.push_back(tri);
            }
        }
    });
    std::vector<Triangle> triangles;
    for (auto& chunk : chunks) {
        triangles.insert(triangles.end(), chunk.begin(), chunk.end());
        std::vector<Triangle>().swap(chunk);
    }
    return triangles;
}

constexpr std::uint32_t NONE = std::numeric_limits<std::uint32_t>::max();

/// Triangles binned into TILE × TILE tiles, in triangle order.
struct Bins
{
    int tilesX = 0, tilesY = 0;
    std::vector<std::vector<std::uint32_t>> tiles;
};

Bins binTriangles(const std::vector<Triangle>& triangles, int width, int height)
{
    // Serial: deterministic order.
    Bins bins;
    bins.tilesX = (width + TILE - 1) / TILE;
    bins.tilesY = (height + TILE - 1) / TILE;
    bins.tiles.resize(std::size_t(bins.tilesX) * std::size_t(bins.tilesY));
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const Triangle& t = triangles[i];
        for (int ty = t.minY / TILE; ty <= t.maxY / TILE; ++ty) {
            for (int tx = t.minX / TILE; tx <= t.maxX / TILE; ++tx) {
                bins.tiles[std::size_t(ty) * std::size_t(bins.tilesX) + std::size_t(tx)].push_back(std::uint32_t(i));
            }
        }
    }
    return bins;
}

/// Visibility in one tile [x0, x1) × [y0, y1) at the samples of `pattern`:
/// GL's top-left rule at each sample position, window depth interpolated
/// linearly in screen space, GL_LESS against a buffer cleared to 1. Fills
/// depth[] and id[], sample s of pixel k at k · pattern.count + s
/// (k TILE-strided).
void resolveTile(const std::vector<Triangle>& triangles, const std::vector<std::uint32_t>& bin, int x0, int y0, int x1,
                 int y1, const SamplePattern& pattern, float* depth, std::uint32_t* id)
{
    const int samples = pattern.count;
    std::fill(depth, depth + TILE * TILE * samples, 1.0f);
    std::fill(id, id + TILE * TILE * samples, NONE);
    for (std::uint32_t index : bin) {
        const Triangle& t = triangles[index];
        const bool tl0 = isTopLeft(t.x[1], t.y[1], t.x[2], t.y[2]);
        const bool tl1 = isTopLeft(t.x[2], t.y[2], t.x[0], t.y[0]);
        const bool tl2 = isTopLeft(t.x[0], t.y[0], t.x[1], t.y[1]);
        const int bx0 = std::max(x0, t.minX), bx1 = std::min(x1 - 1, t.maxX);
        const int by0 = std::max(y0, t.minY), by1 = std::min(y1 - 1, t.maxY);
        for (int py = by0; py <= by1; ++py) {
            for (int px = bx0; px <= bx1; ++px) {
                const int k = ((py - y0) * TILE + (px - x0)) * samples;
                for (int sample = 0; sample < samples; ++sample) {
                    const std::array<int, 2>& o = pattern.offset[std::size_t(sample)];
                    const std::int64_t cx = (std::int64_t(px) << SUBPIXEL_BITS) + o[0];
                    const std::int64_t cy = (std::int64_t(py) << SUBPIXEL_BITS) + o[1];
                    const std::int64_t e0 = edge(t.x[1], t.y[1], t.x[2], t.y[2], cx, cy);
                    const std::int64_t e1 = edge(t.x[2], t.y[2], t.x[0], t.y[0], cx, cy);
                    const std::int64_t e2 = edge(t.x[0], t.y[0], t.x[1], t.y[1], cx, cy);
                    if (!((e0 > 0 || (e0 == 0 && tl0)) && (e1 > 0 || (e1 == 0 && tl1)) &&
                          (e2 > 0 || (e2 == 0 && tl2)))) {
                        continue;
                    }
                    const float fxp = float(px) + float(o[0]) / SUBPIXEL;
                    const float fyp = float(py) + float(o[1]) / SUBPIXEL;
                    const float l0 =
                        ((t.sx[2] - t.sx[1]) * (fyp - t.sy[1]) - (t.sy[2] - t.sy[1]) * (fxp - t.sx[1])) / t.area2;
                    const float l1 =
                        ((t.sx[0] - t.sx[2]) * (fyp - t.sy[2]) - (t.sy[0] - t.sy[2]) * (fxp - t.sx[2])) / t.area2;
                    const float z = l0 * t.z[0] + l1 * t.z[1] + (1.0f - l0 - l1) * t.z[2];
                    if (z < 0.0f || z > 1.0f) continue;
                    if (z < depth[k + sample]) {
                        depth[k + sample] = z;
                        id[k + sample] = index;
                    }
                }
            }
        }
    }
}

/// The mesh's vertices through `matrix` (a view-projection) into clip space.
std::vector<glm::vec4> toClipSpace(const MeshView& mesh, const glm::mat4& matrix)
{
    std::vector<glm::vec4> clip(mesh.vertexCount);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.vertexCount), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            clip[i] = matrix * glm::vec4(mesh.positions[i], 1.0f);
        }
    });
    return clip;
}

/// The sun's depth map (shaders/Shadow.h, step 1), rasterized like any view:
/// resolution², rows top to bottom, 1 where nothing is seen.
CpuShadowMap renderShadowMap(const MeshView& mesh, const shading::ShadowParams& sp)
{
    CpuShadowMap map;
    map.resolution = sp.resolution;
    map.texels.assign(std::size_t(sp.resolution) * std::size_t(sp.resolution), 1.0f);
    const std::vector<glm::vec4> clip = toClipSpace(mesh, sp.lightViewProjection);
    const int size = sp.resolution;
    const std::vector<Triangle> triangles = setupTriangles(mesh, clip, size, size, false);
    const Bins bins = binTriangles(triangles, size, size);
    tbb::parallel_for(0, bins.tilesX * bins.tilesY, [&](int tileIndex) {
        const int x0 = (tileIndex % bins.tilesX) * TILE;
        const int y0 = (tileIndex / bins.tilesX) * TILE;
        const int x1 = std::min(size, x0 + TILE);
        const int y1 = std::min(size, y0 + TILE);
        float depth[TILE * TILE];
        std::uint32_t id[TILE * TILE];
        resolveTile(triangles, bins.tiles[std::size_t(tileIndex)], x0, y0, x1, y1, samplePattern(1), depth, id);
        for (int py = y0; py < y1; ++py) {
            std::copy_n(depth + (py - y0) * TILE, x1 - x0,
                        map.texels.data() + std::size_t(py) * std::size_t(size) + x0);
        }
    });
    return map;
}

/// Throws when an index of `mesh` points beyond its vertices.
void checkMeshIndices(const MeshView& mesh)
{
    for (std::size_t i = 0; i < mesh.indexCount; ++i) {
        if (mesh.indices[i] >= mesh.vertexCount) {
            throw Error(ErrorKind::BadInput, "snapshot: mesh index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", beyond the " + std::to_string(mesh.vertexCount) + " vertices");
        }
    }
}

/// The snapshot's per-frame shading state: viewport, texture space, camera,
/// material, lighting, atmosphere and the maps of `textures` (which must
/// outlive the frame).
Frame makeFrame(const MeshView& mesh, const SnapshotOptions& options, const detail::LayerMaps& textures)
{
    const Material& material = options.material;
    Frame frame;
    frame.width = options.width;
    frame.height = options.height;
    frame.mapScale = material.mapScale;
    const detail::TextureRebase rebase = detail::rebaseTextures(material.mapScale, material.detailScale, mesh.origin);
    frame.textureOffset = rebase.textureOffset;
    frame.detailOffset = rebase.detailOffset;
    frame.tileOffset = rebase.tileOffset;
    frame.cameraPosition = glm::vec3(options.camera.position - mesh.origin);
    frame.material = detail::toShading(material);
    frame.lighting = detail::toShading(options.lighting);
    for (int layer = 0; layer < textures.layerCount; ++layer) {
        for (std::size_t k = 0; k < 9; ++k) {
            frame.maps.layers[std::size_t(layer)][k] = textures.slots[k][std::size_t(layer)].get();
        }
    }
    frame.maps.features = effectiveFeatures(material, options.featureMask);
    if (frame.maps.features & feature::LAYERS) {
        frame.layerSet = detail::makeLayerSet(material, mesh.origin, options.featureMask);
    }
    frame.maps.filter = options.filtering;
    frame.maps.lodLog2 = options.cpuLodLog2;
    frame.atmosphere =
        detail::makeAtmosphereParams(options.lighting, options.camera, mesh.origin, options.width, options.height);
    return frame;
}

/// What every tile of a snapshot reads.
struct SnapshotPass
{
    const Frame& frame;
    const std::vector<Triangle>& triangles;
    const Bins& bins;
    SamplePattern pattern;
    ShadeFunction shade;
    int debugView;
    const CpuShadowMap& shadowMap;
    const shading::ShadowParams& shadow;
    std::array<std::uint8_t, 4> skyBytes; // the flat sky colour
};

/// The background at pixel (px, py): the flat sky colour, or with the
/// atmosphere on the sky pass of sky.frag at the pixel's centre
/// (gl_FragCoord, y up).
void writeSky(const SnapshotPass& pass, int px, int py, std::uint8_t* out)
{
    const Frame& frame = pass.frame;
    if (frame.atmosphere.enabled == 0) {
        std::copy_n(pass.skyBytes.data(), 4, out);
        return;
    }
    const glm::vec2 fragCoord(float(px) + 0.5f, float(frame.height - 1 - py) + 0.5f);
    const glm::vec2 ndc = fragCoord / frame.atmosphere.viewportSize * 2.0f - glm::vec2(1.0f);
    const glm::vec3 c = shading::skyPixel(frame.atmosphere, frame.atmosphere.exposure, ndc);
    out[0] = encode(c.r);
    out[1] = encode(c.g);
    out[2] = encode(c.b);
    out[3] = 255;
}

/// The fragment of triangle `t` at the centre of pixel (px, py), with fine
/// derivatives from the neighbour in the pixel's quad row / column, and the
/// interpolated (not normalized) normal; false where perspective
/// interpolation fails at the centre.
bool fragmentAt(const Frame& frame, const Triangle& t, int px, int py, Fragment& f, glm::vec3& normal)
{
    const int qx = px & ~1;
    const int qy = py & ~1;
    const float cx = float(px) + 0.5f;
    const float cy = float(py) + 0.5f;
    const Interpolated self = interpolate(t, cx, cy);
    if (!self.valid) {
        return false;
    }
    const float nxCentre = float(px == qx ? px + 1 : px - 1) + 0.5f;
    const float nyCentre = float(py == qy ? py + 1 : py - 1) + 0.5f;
    const Interpolated nx = interpolate(t, nxCentre, cy);
    const Interpolated ny = interpolate(t, cx, nyCentre);
    shading::SurfaceInput& s = f.s;
    const glm::vec3 dx = nx.valid ? nx.position - self.position : glm::vec3(0.0f);
    const glm::vec3 dy = ny.valid ? ny.position - self.position : glm::vec3(0.0f);
    f.world.p = self.position;
    f.world.detailOffset = glm::vec3(0.0f);
    f.world.tileOffset = glm::vec3(0.0f);
    f.world.dpdx = px == qx ? dx : -dx;
    f.world.dpdy = py == qy ? dy : -dy;
    f.world.n = shading::safeNormalize(self.normal, glm::vec3(0.0f, 1.0f, 0.0f));
    f.world.viewDir = shading::safeNormalize(frame.cameraPosition - self.position, f.world.n);
    s = f.world;
    s.p = self.position * frame.mapScale + frame.textureOffset;
    s.detailOffset = frame.detailOffset;
    s.tileOffset = frame.tileOffset;
    s.dpdx = f.world.dpdx * frame.mapScale;
    s.dpdy = f.world.dpdy * frame.mapScale;
    f.surface = self.surface;
    f.landform = self.landform;
    f.rock = self.rock;
    normal = self.normal;
    return true;
}

/// Counts one shaded pixel and what a naive triplanar shader would have
/// fetched for it: all three projections of every map it reads (three taps
/// each with anti-tiling), of every layer it evaluates, an upper bound of
/// what the header fetched. Clears the maps' per-fragment record.
void countShadedPixel(CpuMaps& maps, CpuRenderStats& counted)
{
    ++counted.shadedPixels;
    for (std::size_t l = 0; l < maps.sampled.size(); ++l) {
        const std::uint64_t taps = (maps.antiTiled >> l) & 1u ? 3u : 1u;
        counted.naiveFetches += 3u * taps * std::uint64_t(std::popcount(maps.sampled[l]));
        maps.sampled[l] = 0;
    }
    maps.antiTiled = 0;
}

/// Triangle `index` shaded at the centre of pixel (px, py), as GL shades a
/// multisampled fragment (not at its samples); false for a centre where
/// perspective interpolation fails (the sky then). `maps` is the tile's
/// copy, counting its fetches.
bool shadeAt(const SnapshotPass& pass, CpuMaps& maps, CpuRenderStats& counted, std::uint32_t index, int px, int py,
             glm::vec3& c)
{
    const Frame& frame = pass.frame;
    Fragment f;
    glm::vec3 normal;
    if (!fragmentAt(frame, pass.triangles[index], px, py, f, normal)) {
        return false;
    }
    if (pass.debugView != shading::DEBUG_VIEW_SHADED) {
        const std::uint32_t selected = maps.features;
        c = shading::fragmentDebugColor(evaluateWith<feature::ALL>(frame, maps, f), f.landform, f.rock, pass.debugView);
        maps.features = selected;
    } else {
        // The interpolated (not the normal-mapped) normal biases the lookup.
        const float visibility = shading::sunVisibility(pass.shadowMap, pass.shadow, f.world.p, normal);
        c = pass.shade(frame, maps, f, shading::shadowedLighting(frame.lighting, visibility));
    }
    countShadedPixel(maps, counted);
    return true;
}

/// Pixel (px, py) of a tile: with several samples, each triangle that covers
/// any of the pixel's samples (`ids`, NONE for the sky) is shaded once and
/// stored at the samples it covers, as 8-bit sRGB like GL's framebuffer; the
/// pixel is then resolved to the rounded mean of the stored bytes, as
/// llvmpipe's resolving blit does (averaging in linear light instead
/// measured 48.1 dB against it rather than 54.0 dB on the default scene).
void resolvePixel(const SnapshotPass& pass, CpuMaps& maps, CpuRenderStats& counted, const std::uint32_t* ids, int px,
                  int py, std::uint8_t* out)
{
    const int samples = pass.pattern.count;
    std::uint32_t seen[MAX_SAMPLES];
    int cover[MAX_SAMPLES];
    int distinct = 0;
    int skySamples = 0;
    for (int sample = 0; sample < samples; ++sample) {
        if (ids[sample] == NONE) {
            ++skySamples;
            continue;
        }
        int i = 0;
        while (i < distinct && seen[i] != ids[sample]) ++i;
        if (i == distinct) {
            seen[distinct] = ids[sample];
            cover[distinct++] = 0;
        }
        ++cover[i];
    }
    glm::vec3 c;
    if (distinct == 1 && skySamples == 0) { // the inside of a surface: one fragment, no resolve
        if (shadeAt(pass, maps, counted, seen[0], px, py, c)) {
            out[0] = encode(c.r);
            out[1] = encode(c.g);
            out[2] = encode(c.b);
            out[3] = 255;
        } else {
            writeSky(pass, px, py, out);
        }
        return;
    }
    std::uint8_t sky[4];
    writeSky(pass, px, py, sky);
    int sum[3] = {skySamples * sky[0], skySamples * sky[1], skySamples * sky[2]};
    for (int i = 0; i < distinct; ++i) {
        const bool shaded = shadeAt(pass, maps, counted, seen[i], px, py, c);
        const int bytes[3] = {shaded ? encode(c.r) : sky[0], shaded ? encode(c.g) : sky[1],
                              shaded ? encode(c.b) : sky[2]};
        for (int ch = 0; ch < 3; ++ch) sum[ch] += cover[i] * bytes[ch];
    }
    for (int ch = 0; ch < 3; ++ch) out[ch] = std::uint8_t((sum[ch] + samples / 2) / samples);
    out[3] = 255;
}

/// One TILE × TILE tile of the snapshot: visibility, then shading in 2×2
/// quads (tile origins are even), into `image`; counts into `counted`.
void renderTile(const SnapshotPass& pass, int tileIndex, Image& image, CpuRenderStats& counted)
{
    const int tilesX = pass.bins.tilesX;
    const int x0 = (tileIndex % tilesX) * TILE;
    const int y0 = (tileIndex / tilesX) * TILE;
    const int x1 = std::min(pass.frame.width, x0 + TILE);
    const int y1 = std::min(pass.frame.height, y0 + TILE);
    const int samples = pass.pattern.count;
    CpuMaps maps = pass.frame.maps; // this tile's fetch counters
    std::vector<float> depth(std::size_t(TILE * TILE * samples));
    std::vector<std::uint32_t> id(std::size_t(TILE * TILE * samples));
    resolveTile(pass.triangles, pass.bins.tiles[std::size_t(tileIndex)], x0, y0, x1, y1, pass.pattern, depth.data(),
                id.data());
    for (int py = y0; py < y1; ++py) {
        for (int px = x0; px < x1; ++px) {
            const std::uint32_t* ids = id.data() + std::size_t(((py - y0) * TILE + (px - x0)) * samples);
            resolvePixel(pass, maps, counted, ids, px, py, image.at(px, py));
        }
    }
    counted.textureFetches = maps.fetches;
}

/// The tiles' counts summed in tile order: the same sums on any thread count.
CpuRenderStats sumTileStats(const std::vector<CpuRenderStats>& tileStats)
{
    CpuRenderStats total{};
    for (const CpuRenderStats& t : tileStats) {
        total.shadedPixels += t.shadedPixels;
        total.textureFetches += t.textureFetches;
        total.naiveFetches += t.naiveFetches;
    }
    return total;
}

} // namespace

std::vector<glm::vec2> cpuSamplePositions(int samples)
{
    const SamplePattern pattern = samplePattern(samples);
    std::vector<glm::vec2> positions;
    for (int i = 0; i < pattern.count; ++i) {
        const std::array<int, 2>& o = pattern.offset[std::size_t(i)];
        positions.emplace_back(float(o[0]) / SUBPIXEL, 1.0f - float(o[1]) / SUBPIXEL);
    }
    return positions;
}

Image renderSnapshotCpu(const MeshView& mesh, const SnapshotOptions& options, CpuRenderStats* stats)
{
    checkSnapshotOptions(options);
    checkMeshIndices(mesh);
    const int width = options.width;
    const int height = options.height;
    const detail::LayerMaps textures = detail::resolveLayerMaps(options.material);
    const Frame frame = makeFrame(mesh, options, textures);
    const int debugView = int(options.debugView);

    // Shadow pass.
    const shading::ShadowParams shadow =
        detail::makeShadowParams(detail::meshBounds(mesh), options.lighting, options.shadows);
    CpuShadowMap shadowMap;
    if (shadow.enabled != 0 && debugView == shading::DEBUG_VIEW_SHADED) { // debug views are unlit
        shadowMap = renderShadowMap(mesh, shadow);
    }

    // Visibility: vertices to clip space, triangles set up and binned.
    const glm::mat4 viewProjection =
        projectionMatrix(options.camera, double(width) / double(height)) * viewMatrix(options.camera, mesh.origin);
    const std::vector<glm::vec4> clip = toClipSpace(mesh, viewProjection);
    const SamplePattern pattern = samplePattern(options.samples);
    const std::vector<Triangle> triangles = setupTriangles(mesh, clip, width, height, true, pattern.count > 1);
    const Bins bins = binTriangles(triangles, width, height);

    const glm::vec3 sky = options.lighting.skyColor;
    const SnapshotPass pass{frame,
                            triangles,
                            bins,
                            pattern,
                            shadeFunctionFor(frame.maps.features),
                            debugView,
                            shadowMap,
                            shadow,
                            {encode(sky.r), encode(sky.g), encode(sky.b), 255}};
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(std::size_t(width) * std::size_t(height) * 4);
    std::vector<CpuRenderStats> tileStats(std::size_t(bins.tilesX) * std::size_t(bins.tilesY));
    tbb::parallel_for(0, bins.tilesX * bins.tilesY,
                      [&](int tileIndex) { renderTile(pass, tileIndex, image, tileStats[std::size_t(tileIndex)]); });
    if (stats) {
        *stats = sumTileStats(tileStats);
    }
    return image;
}

} // namespace strata::render
