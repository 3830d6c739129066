// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The per-frame uniform block shared by the terrain vertex and fragment
// stages. std140, mirrored by strata::render::detail::FrameBlock
// (render/src/UniformBlocks.h, which checks every offset); binding points:
//   0 FrameBlock, 1 MaterialBlock, 2 LightingBlock (terrain.frag).
// Texture units 0..8 hold the material's maps (MAP_* slots).

layout(std140, binding = 0) uniform FrameBlock
{
    mat4 viewProjection;  // projection · view(origin)
    vec4 cameraPosition;  // xyz: metres, relative to the mesh origin
    vec4 textureOffset;   // xyz: fract(origin · mapScale), computed in double (a tile-aligned rebasing)
    vec4 wireColor;       // linear RGBA of the wireframe overlay
    float mapScale;       // texture repeats per metre
    int debugView;        // DEBUG_VIEW_* (TriplanarMaterial.h); 0 = shaded
    int wireframePass;    // 1 while drawing the wireframe overlay
    int explicitLod;      // 1: maps sampled at the level of detail computed as the CPU reference does (terrain.frag)
    vec4 detailOffset;    // xyz: fract(floor(origin · mapScale) · detailScale), computed in double
    vec4 tileOffset;      // xyz: floor(origin · mapScale) modulo 256 (anti-tiling's lattice)
} uFrame;
