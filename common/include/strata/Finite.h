// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Finiteness of GLM vectors (checks of user input and of results).

#include <glm/vec3.hpp>

#include <cmath>

namespace strata {

/// True when every component is finite (no NaN, no infinity).
inline bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

} // namespace strata
