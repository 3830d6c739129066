// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// One triangle covering the viewport (no vertex buffer: gl_VertexID 0..2).
// Used by the sky pass (sky.frag) and by the shading probe
// (tests/render/ShadingProbeTest.cpp), where every pixel of the float
// target is one sample point.

void main()
{
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0f - vec2(1.0f), 0.0f, 1.0f);
}
