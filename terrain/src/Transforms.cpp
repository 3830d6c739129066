#include <strata/terrain/Transforms.h>

#include <strata/Error.h>

#include <cmath>
#include <sstream>

namespace strata::terrain {

namespace {

std::string show(double v)
{
    std::ostringstream out;
    out << v;
    return out.str();
}

} // namespace

WarpField::WarpField(DensityFieldPtr child, std::uint64_t seed, const WarpOptions& options)
    : mChild(std::move(child))
    , mOptions(options)
    , mX(deriveSeed(seed, 1), options.noise)
    , mY(deriveSeed(seed, 2), options.noise)
    , mZ(deriveSeed(seed, 3), options.noise)
{
    if (!(std::isfinite(options.amplitude) && options.amplitude >= 0.0)) {
        throw Error("amplitude = " + show(options.amplitude) + " must be a finite number >= 0");
    }
    if (!(std::isfinite(options.wavelength) && options.wavelength > 0.0)) {
        throw Error("wavelength = " + show(options.wavelength) + " must be a finite number > 0");
    }
    if (!(std::isfinite(options.vertical) && options.vertical >= 0.0)) {
        throw Error("vertical = " + show(options.vertical) + " must be a finite number >= 0");
    }
    // ‖J‖ <= 1 + ‖amplitude·∇(f1, v·f2, f3)/wavelength‖_F.
    const double lf = mX.lipschitz(3) / options.wavelength;
    mStretch = 1.0 + options.amplitude * lf * std::sqrt(2.0 + options.vertical * options.vertical);
}

glm::dvec3 WarpField::warp(const glm::dvec3& p) const
{
    const glm::dvec3 q = p / mOptions.wavelength;
    const double y = mOptions.vertical != 0.0 ? mOptions.vertical * mY(q) : 0.0;
    return p + mOptions.amplitude * glm::dvec3(mX(q), y, mZ(q));
}

double WarpField::density(const glm::dvec3& p) const
{
    return mChild->density(warp(p));
}

double WarpField::distanceBound(const glm::dvec3& p) const
{
    return mChild->distanceBound(warp(p)) / mStretch;
}

TerraceField::TerraceField(DensityFieldPtr child, double step, double sharpness)
    : mChild(std::move(child)), mStep(step), mSharpness(sharpness)
{
    if (!(std::isfinite(step) && step > 0.0)) throw Error("step = " + show(step) + " must be a finite number > 0");
    if (!(std::isfinite(sharpness) && sharpness >= 1.0 && sharpness <= 64.0)) {
        throw Error("sharpness = " + show(sharpness) + " is out of range [1, 64]");
    }
}

double TerraceField::terrace(double y) const
{
    const double s = y / mStep, k = std::floor(s);
    return mStep * (k + std::pow(s - k, mSharpness));
}

double TerraceField::density(const glm::dvec3& p) const
{
    return mChild->density({p.x, terrace(p.y), p.z});
}

double TerraceField::distanceBound(const glm::dvec3& p) const
{
    return mChild->distanceBound({p.x, terrace(p.y), p.z}) / std::max(1.0, mSharpness);
}

} // namespace strata::terrain
