#pragma once
/// \file
/// The default terrain: an fBm heightfield with spaghetti-style cave tunnels
/// carved out of it.

#include <strata/terrain/DensityField.h>
#include <strata/terrain/Noise.h>

#include <cstdint>

namespace strata::terrain {

/// A heightfield y = h(x, z), all lengths in metres.
struct HeightfieldOptions
{
    double baseHeight = 0.0;   ///< mean surface height
    double amplitude = 24.0;   ///< peak deviation from baseHeight
    double wavelength = 96.0;  ///< horizontal size of the largest features
    FbmOptions fbm{6, 2.0, 0.5};
};

/// Tunnels where two independent 3D noise fields are both near zero: long,
/// winding, connected tubes that cross the surface here and there.
struct CaveOptions
{
    bool enabled = true;
    double wavelength = 48.0;  ///< horizontal size of the tunnel meanders (m)
    double radius = 3.0;       ///< approximate tunnel radius (m)
    double verticalSquash = 1.6; ///< >1 makes tunnels run more horizontally
    double maxHeight = 1e30;   ///< no tunnels above this height (m)
};

struct TerrainOptions
{
    std::uint64_t seed = 1;
    HeightfieldOptions height;
    CaveOptions caves;
};

/// Heightfield minus caves, as a distance-like field (negative in rock).
class TerrainField final : public DensityField
{
public:
    explicit TerrainField(const TerrainOptions& options);

    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return 1.0; }

    /// The heightfield alone: surface height at (x, z), metres.
    double height(double x, double z) const;

    /// The cave term alone: negative inside a tunnel, in metres (approx.).
    double caveDistance(const glm::dvec3& p) const;

    const TerrainOptions& options() const { return mOptions; }

private:
    TerrainOptions mOptions;
    double mHeightScale; ///< 1 / Lipschitz bound of (y − h), keeps density 1-Lipschitz
    double mCaveScale;   ///< the same for the cave term
};

} // namespace strata::terrain
