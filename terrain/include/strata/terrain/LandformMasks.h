// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The masks a landform pass (erosion) leaves, readable at any world column:
/// what texturing rules key on, the way Gaea's and World Machine's flow,
/// wear and deposition maps drive their materials.

#include <glm/vec4.hpp>

#include <cstddef>

namespace strata::terrain {

/// Implemented by nodes that know their landform masks (the `erode` node).
/// The scene finds one in the node tree with dynamic_cast.
class LandformMasks
{
public:
    virtual ~LandformMasks() = default;
    /// At n world columns (x[i], z[i]), metres, into out[0, n):
    ///  - x, flow: log10 of the drainage area in m² (0 on a ridge of one
    ///    square metre; about 4 on a hillside gully, 6 to 7 on a main river
    ///    of a 4 km world);
    ///  - y, wear: depth eroded since the start, metres (>= 0);
    ///  - z, deposition: sediment thickness laid down, metres (>= 0);
    ///  - w, water: 0 dry .. 1 in a river (discharge above the node's
    ///    threshold) or a filled lake.
    /// Smoothly interpolated (no cell steps); clamped at the domain's edge.
    /// Thread-safe; the same bits on any thread count.
    virtual void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const = 0;
};

} // namespace strata::terrain
