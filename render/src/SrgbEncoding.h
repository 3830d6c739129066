// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: 8-bit encoding of colour and data values, shared by the
// texture builder and the map file reader.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace strata::render::detail {

/// The sRGB encoding (IEC 61966-2-1) of a linear value, clamped to [0, 1].
inline float linearToSrgbValue(float c)
{
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

/// [0, 1] to 0..255, rounded; values outside are clamped.
inline std::uint8_t toByte(float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

} // namespace strata::render::detail
