// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Terrain vertex shader. Positions are world metres relative to the mesh
// origin; the view matrix is relative to the same origin (computed in double
// on the CPU), so large worlds keep their precision. Uniforms: FrameBlock
// (TerrainFrame.glsl).

layout(location = 0) in vec3 aPosition; // metres, relative to the mesh origin
layout(location = 1) in vec3 aNormal;   // unit, world space
layout(location = 2) in vec2 aSurface;  // cavity, cover (MeshView::surface; (0, 0) when the mesh has none)
layout(location = 3) in vec4 aLandform; // flow, wear, deposition, water (MeshView::landform; 0 when the mesh has none)
layout(location = 4) in vec2 aRock;     // hardness, bed (MeshView::rock; 0 when the mesh has none)

out vec3 vTexturePosition; // texture space: (world position) · mapScale, mod 1
out vec3 vNormal;
out vec3 vPosition;        // metres, relative to the mesh origin
out vec2 vSurface;
out vec4 vLandform;
out vec2 vRock;

void main()
{
    vTexturePosition = aPosition * uFrame.mapScale + vec3(uFrame.textureOffset);
    vNormal = aNormal;
    vPosition = aPosition;
    vSurface = aSurface;
    vLandform = aLandform;
    vRock = aRock;
    gl_Position = uFrame.viewProjection * vec4(aPosition, 1.0f);
}
