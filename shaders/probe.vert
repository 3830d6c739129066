// Shading probe (tests/render/ShadingProbeTest.cpp): one triangle covering
// the viewport; every pixel of the float target is one sample point.

void main()
{
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0f - vec2(1.0f), 0.0f, 1.0f);
}
