// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The sky pass (Atmosphere.h): drawn over the whole viewport before the
// terrain when the atmosphere is on, instead of clearing to a flat colour.
// Each pixel's view ray comes from its centre in device coordinates, as on
// the CPU renderer. Output is linear; the sRGB framebuffer encodes it.

layout(std140, binding = 4) uniform AtmosphereBlock
{
    AtmosphereParams uAtmosphere;
};

layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 ndc = gl_FragCoord.xy / uAtmosphere.viewportSize * 2.0f - vec2(1.0f);
    fragColor = vec4(skyPixel(uAtmosphere, uAtmosphere.exposure, ndc), 1.0f);
}
