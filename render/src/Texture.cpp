// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/Texture.h>

#include <strata/Error.h>

#include "SrgbEncoding.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace strata::render {

using detail::linearToSrgbValue;
using detail::toByte;

namespace {

const std::array<float, 256>& srgbTable()
{
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double c = i / 255.0;
            t[std::size_t(i)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

void checkImage(const Image& image, const char* what)
{
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
        throw Error(ErrorKind::BadInput, std::string(what) + ": not a valid RGBA8 image (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ")");
    }
}

bool isNormal(MapKind kind)
{
    return kind == MapKind::Normal || kind == MapKind::DetailNormal;
}

} // namespace

bool isSrgb(MapKind kind)
{
    return kind == MapKind::Albedo || kind == MapKind::Emission;
}

float srgbByteToLinear(std::uint8_t value)
{
    return srgbTable()[value];
}

TexturePtr makeTexture(const Image& image, MapKind kind, const MipOptions& options)
{
    checkImage(image, "texture");
    auto texture = std::make_shared<Texture>();
    texture->kind = kind;
    texture->srgb = isSrgb(kind);
    Texture::Level base;
    base.width = image.width;
    base.height = image.height;
    base.texels.resize(image.pixels.size());
    const std::size_t rowBytes = std::size_t(image.width) * 4;
    for (int y = 0; y < image.height; ++y) {
        std::copy_n(image.pixels.data() + std::size_t(image.height - 1 - y) * rowBytes, rowBytes,
                    base.texels.data() + std::size_t(y) * rowBytes);
    }
    texture->levels.push_back(std::move(base));

    const bool fade = kind == MapKind::Detail || kind == MapKind::DetailNormal;
    const float* table = srgbTable().data();
    for (int level = 1;; ++level) {
        const Texture::Level& src = texture->levels.back();
        if (src.width == 1 && src.height == 1) {
            break;
        }
        Texture::Level dst;
        dst.width = std::max(1, src.width / 2);
        dst.height = std::max(1, src.height / 2);
        dst.texels.resize(std::size_t(dst.width) * std::size_t(dst.height) * 4);
        float fadeAmount = 0.0f;
        if (fade) {
            const float span = options.detailFadeEnd - options.detailFadeStart;
            fadeAmount = span <= 0.0f ? (float(level) >= options.detailFadeStart ? 1.0f : 0.0f)
                                      : std::clamp((float(level) - options.detailFadeStart) / span, 0.0f, 1.0f);
        }
        for (int y = 0; y < dst.height; ++y) {
            for (int x = 0; x < dst.width; ++x) {
                float sum[4] = {0, 0, 0, 0};
                for (int dy = 0; dy < 2; ++dy) {
                    for (int dx = 0; dx < 2; ++dx) {
                        const int sx = std::min(2 * x + dx, src.width - 1);
                        const int sy = std::min(2 * y + dy, src.height - 1);
                        const std::uint8_t* t = src.texels.data() + (std::size_t(sy) * src.width + sx) * 4;
                        for (int c = 0; c < 4; ++c) {
                            sum[c] += (texture->srgb && c < 3) ? table[t[c]] : t[c] / 255.0f;
                        }
                    }
                }
                float v[4];
                for (int c = 0; c < 4; ++c) {
                    v[c] = sum[c] * 0.25f;
                }
                if (isNormal(kind)) {
                    glm::vec3 n(v[0] * 2.0f - 1.0f, v[1] * 2.0f - 1.0f, v[2] * 2.0f - 1.0f);
                    const float len = glm::length(n);
                    n = len > 1e-6f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
                    if (fadeAmount > 0.0f) {
                        n = glm::normalize(glm::mix(n, glm::vec3(0.0f, 0.0f, 1.0f), fadeAmount) +
                                           glm::vec3(0.0f, 0.0f, 1e-6f));
                    }
                    v[0] = n.x * 0.5f + 0.5f;
                    v[1] = n.y * 0.5f + 0.5f;
                    v[2] = n.z * 0.5f + 0.5f;
                } else if (fadeAmount > 0.0f) {
                    for (int c = 0; c < 3; ++c) {
                        v[c] += (0.5f - v[c]) * fadeAmount;
                    }
                }
                std::uint8_t* out = dst.texels.data() + (std::size_t(y) * dst.width + x) * 4;
                for (int c = 0; c < 4; ++c) {
                    out[c] = toByte((texture->srgb && c < 3) ? linearToSrgbValue(v[c]) : v[c]);
                }
            }
        }
        texture->levels.push_back(std::move(dst));
    }
    return texture;
}

TexturePtr makeConstantTexture(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a, MapKind kind)
{
    Image image;
    image.width = 1;
    image.height = 1;
    image.pixels = {r, g, b, a};
    return makeTexture(image, kind);
}

ChannelSource parseChannelSource(const std::string& text, const std::string& what)
{
    std::string t;
    for (char c : text) {
        if (c != ' ') t += char(std::tolower(static_cast<unsigned char>(c)));
    }
    ChannelSource source;
    if (t.rfind("1-", 0) == 0 && t.size() == 3) {
        source.invert = true;
        t = t.substr(2);
    }
    static const std::string NAMES = "rgba01";
    if (t.size() != 1 || NAMES.find(t[0]) == std::string::npos) {
        throw Error(ErrorKind::BadInput, what + " = '" + text + "' must be r, g, b, a, 0, 1 or 1-r, 1-g, 1-b, 1-a");
    }
    source.channel = int(NAMES.find(t[0]));
    return source;
}

Image remapChannels(const Image& image, const ChannelMapping& mapping)
{
    Image out = image;
    const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* src = image.pixels.data() + i * 4;
        std::uint8_t* dst = out.pixels.data() + i * 4;
        for (int c = 0; c < 4; ++c) {
            const ChannelSource& s = mapping.channels[c];
            std::uint8_t v = s.channel < 4 ? src[s.channel] : (s.channel == 4 ? 0 : 255);
            dst[c] = s.invert ? std::uint8_t(255 - v) : v;
        }
    }
    return out;
}

void flipGreen(Image& image)
{
    for (std::size_t i = 1; i < image.pixels.size(); i += 4) {
        image.pixels[i] = std::uint8_t(255 - image.pixels[i]);
    }
}

std::uint64_t textureBytes(const TexturePtr& texture)
{
    std::uint64_t bytes = 0;
    if (texture) {
        for (const Texture::Level& level : texture->levels) bytes += level.texels.size();
    }
    return bytes;
}

Image packMohs(const Image* metallic, const Image* occlusion, const Image* height, const Image* smoothness)
{
    const Image* images[4] = {metallic, occlusion, height, smoothness};
    const std::uint8_t defaults[4] = {0, 255, 128, 128};
    const Image* first = nullptr;
    for (const Image* image : images) {
        if (image) {
            checkImage(*image, "packMohs");
            if (first && (image->width != first->width || image->height != first->height)) {
                throw Error(ErrorKind::BadInput, "packMohs: images differ in size (" + std::to_string(first->width) + "x" +
                            std::to_string(first->height) + " vs " + std::to_string(image->width) + "x" +
                            std::to_string(image->height) + ")");
            }
            first = first ? first : image;
        }
    }
    Image out;
    out.width = first ? first->width : 1;
    out.height = first ? first->height : 1;
    out.pixels.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
    for (std::size_t i = 0; i < std::size_t(out.width) * std::size_t(out.height); ++i) {
        for (int c = 0; c < 4; ++c) {
            out.pixels[i * 4 + std::size_t(c)] = images[c] ? images[c]->pixels[i * 4] : defaults[c];
        }
    }
    return out;
}

// ---------------------------------------------------------------------------

namespace {

inline glm::vec4 fetch(const Texture& texture, const Texture::Level& level, int i, int j)
{
    const std::uint8_t* t = level.texels.data() + (std::size_t(j) * std::size_t(level.width) + std::size_t(i)) * 4;
    if (texture.srgb) {
        const float* table = srgbTable().data();
        return {table[t[0]], table[t[1]], table[t[2]], t[3] * (1.0f / 255.0f)};
    }
    constexpr float S = 1.0f / 255.0f;
    return {t[0] * S, t[1] * S, t[2] * S, t[3] * S};
}

inline int wrapIndex(int i, int n)
{
    const int m = i % n;
    return m < 0 ? m + n : m;
}

inline float fractOf(float x)
{
    return x - std::floor(x);
}

} // namespace

glm::vec4 sampleBilinear(const Texture& texture, int levelIndex, glm::vec2 uv)
{
    const Texture::Level& level = texture.levels[std::size_t(levelIndex)];
    // Wrap first (exactly periodic), then position in texels.
    const float u = fractOf(uv.x) * float(level.width) - 0.5f;
    const float v = fractOf(uv.y) * float(level.height) - 0.5f;
    const float fu = std::floor(u);
    const float fv = std::floor(v);
    const float a = u - fu;
    const float b = v - fv;
    const int i0 = wrapIndex(int(fu), level.width);
    const int j0 = wrapIndex(int(fv), level.height);
    const int i1 = wrapIndex(i0 + 1, level.width);
    const int j1 = wrapIndex(j0 + 1, level.height);
    const glm::vec4 t00 = fetch(texture, level, i0, j0);
    const glm::vec4 t10 = fetch(texture, level, i1, j0);
    const glm::vec4 t01 = fetch(texture, level, i0, j1);
    const glm::vec4 t11 = fetch(texture, level, i1, j1);
    return (t00 * (1.0f - a) + t10 * a) * (1.0f - b) + (t01 * (1.0f - a) + t11 * a) * b;
}

float textureLod(const Texture& texture, glm::vec2 dUVdx, glm::vec2 dUVdy, LodLog2 log2)
{
    const float w = float(texture.width());
    const float h = float(texture.height());
    const float x2 = dUVdx.x * w * dUVdx.x * w + dUVdx.y * h * dUVdx.y * h;
    const float y2 = dUVdy.x * w * dUVdy.x * w + dUVdy.y * h * dUVdy.y * h;
    const float rho2 = std::max(x2, y2);
    if (!(rho2 > 0.0f)) { // zero or NaN: the finest level
        return -1000.0f;
    }
    if (std::isinf(rho2)) { // the coarsest
        return 1000.0f;
    }
    if (log2 == LodLog2::Exact) {
        return 0.5f * std::log2(rho2);
    }
    // llvmpipe: the exponent plus the mantissa's fraction.
    int exponent = 0;
    const float mantissa = std::frexp(rho2, &exponent); // rho2 = mantissa · 2^exponent, mantissa in [0.5, 1)
    return 0.5f * (float(exponent - 1) + (2.0f * mantissa - 1.0f));
}

glm::vec4 sampleTrilinear(const Texture& texture, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy, LodLog2 log2)
{
    const float lambda = textureLod(texture, dUVdx, dUVdy, log2);
    const int last = int(texture.levels.size()) - 1;
    if (!(lambda > 0.0f) || last == 0) {
        return sampleBilinear(texture, 0, uv);
    }
    if (lambda >= float(last)) {
        return sampleBilinear(texture, last, uv);
    }
    const int d1 = int(std::floor(lambda));
    const float t = lambda - float(d1);
    const glm::vec4 a = sampleBilinear(texture, d1, uv);
    if (t == 0.0f) {
        return a;
    }
    const glm::vec4 b = sampleBilinear(texture, d1 + 1, uv);
    return a * (1.0f - t) + b * t;
}

glm::vec4 sampleBilinearNearestMip(const Texture& texture, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy,
                                   LodLog2 log2)
{
    const float lambda = textureLod(texture, dUVdx, dUVdy, log2);
    const int last = int(texture.levels.size()) - 1;
    if (!(lambda > 0.5f) || last == 0) {
        return sampleBilinear(texture, 0, uv);
    }
    if (lambda > float(last) + 0.5f) {
        return sampleBilinear(texture, last, uv);
    }
    return sampleBilinear(texture, int(std::ceil(lambda + 0.5f)) - 1, uv);
}

glm::vec4 sampleFiltered(const Texture& texture, TextureFilter filter, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy,
                         LodLog2 log2)
{
    return filter == TextureFilter::Bilinear ? sampleBilinearNearestMip(texture, uv, dUVdx, dUVdy, log2)
                                             : sampleTrilinear(texture, uv, dUVdx, dUVdy, log2);
}

} // namespace strata::render
