// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "MaterialMaps.h"

#include <strata/Error.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <string>

namespace strata::render::detail {

namespace {

const char* const SLOT_NAMES[9] = {"albedo",     "mask",   "normal",        "top_albedo", "top_mask",
                                   "top_normal", "detail", "detail_normal", "emission"};

/// The neutral value of an absent map, per slot.
const TexturePtr& standIn(int slot)
{
    static const TexturePtr GREY = makeConstantTexture(200, 200, 200, 255, MapKind::Albedo);
    static const TexturePtr WHITE_MASK = makeConstantTexture(255, 255, 255, 255, MapKind::Mask);
    static const TexturePtr FLAT = makeConstantTexture(128, 128, 255, 255, MapKind::Normal);
    static const TexturePtr NEUTRAL = makeConstantTexture(128, 128, 128, 255, MapKind::Detail);
    static const TexturePtr BLACK = makeConstantTexture(0, 0, 0, 255, MapKind::Emission);
    static const TexturePtr* const BY_SLOT[9] = {&GREY, &WHITE_MASK, &FLAT, &GREY, &WHITE_MASK,
                                                 &FLAT, &NEUTRAL,    &FLAT, &BLACK};
    return *BY_SLOT[slot];
}

/// The slot's own maps of one material, null where absent (top maps fall
/// back to the side maps).
std::array<TexturePtr, 9> ownMaps(const Material& m)
{
    std::array<TexturePtr, 9> maps{m.albedo, m.mask, m.normal, m.topAlbedo, m.topMask, m.topNormal,
                                   m.detail, m.detailNormal, m.emission};
    for (int k = 0; k < 3; ++k) {
        if (!maps[std::size_t(3 + k)]) maps[std::size_t(3 + k)] = maps[std::size_t(k)];
    }
    return maps;
}

std::string layerName(const Material& material, int layer)
{
    if (layer == 0) return "base";
    const std::string& name = material.layers[std::size_t(layer - 1)].name;
    return name.empty() ? std::to_string(layer) : name;
}

std::string size(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

/// `texture` from level `first` on, `count` levels (shares nothing: a copy).
TexturePtr levelsFrom(const Texture& texture, std::size_t first, std::size_t count)
{
    auto out = std::make_shared<Texture>();
    out->kind = texture.kind;
    out->srgb = texture.srgb;
    out->levels.assign(texture.levels.begin() + std::ptrdiff_t(first),
                       texture.levels.begin() + std::ptrdiff_t(first + count));
    return out;
}

/// A constant texture of `value` (one RGBA8 texel) with `count` levels from w × h.
TexturePtr constantLevels(const Texture& value, int w, int h, std::size_t count)
{
    auto out = std::make_shared<Texture>();
    out->kind = value.kind;
    out->srgb = value.srgb;
    const std::uint8_t* texel = value.levels[0].texels.data();
    for (std::size_t i = 0; i < count; ++i) {
        Texture::Level level;
        level.width = w;
        level.height = h;
        level.texels.resize(std::size_t(w) * std::size_t(h) * 4);
        for (std::size_t t = 0; t < level.texels.size(); t += 4) std::copy_n(texel, 4, level.texels.data() + t);
        out->levels.push_back(std::move(level));
        w = std::max(w / 2, 1);
        h = std::max(h / 2, 1);
    }
    return out;
}

/// The textures resolveLayerMaps() derives (a map from a lower level, a
/// stand-in at a slot's size), kept while in use, so that the same material
/// resolves to the same texture objects every time: the GL renderer then
/// keeps its texture arrays between setMaterial() calls (a turntable sets the
/// material once per frame) instead of uploading them again.
class DerivedTextures
{
public:
    template <class Make>
    TexturePtr get(const TexturePtr& source, std::size_t first, int w, int h, std::size_t count, Make make)
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        for (auto it = mEntries.begin(); it != mEntries.end();) {
            const TexturePtr alive = it->source.lock();
            const TexturePtr derived = it->derived.lock();
            if (!alive || !derived) {
                it = mEntries.erase(it); // its source or its result is gone
                continue;
            }
            if (alive == source && it->first == first && it->w == w && it->h == h && it->count == count) {
                return derived;
            }
            ++it;
        }
        TexturePtr made = make();
        mEntries.push_back({source, made, first, w, h, count});
        return made;
    }

private:
    struct Entry
    {
        std::weak_ptr<const Texture> source;
        std::weak_ptr<const Texture> derived;
        std::size_t first;
        int w, h;
        std::size_t count;
    };
    std::mutex mMutex;
    std::vector<Entry> mEntries;
};

DerivedTextures& derivedTextures()
{
    static DerivedTextures cache;
    return cache;
}

} // namespace

std::array<TexturePtr, 9> resolveMaps(const Material& m)
{
    std::array<TexturePtr, 9> maps = ownMaps(m);
    for (int k = 0; k < 9; ++k) {
        if (!maps[std::size_t(k)]) maps[std::size_t(k)] = standIn(k);
    }
    return maps;
}

std::array<SlotPlan, 9> planLayerSlots(const Material& material)
{
    const int layerCount = 1 + int(material.layers.size());
    std::vector<std::array<TexturePtr, 9>> own;
    own.push_back(ownMaps(material));
    for (const MaterialLayer& layer : material.layers) own.push_back(ownMaps(layer.material));

    std::array<SlotPlan, 9> plans;
    for (int k = 0; k < 9; ++k) {
        SlotPlan& plan = plans[std::size_t(k)];
        plan.textures.resize(std::size_t(layerCount));
        plan.first.assign(std::size_t(layerCount), 0);
        // The smallest present map sets the slot's size.
        int smallest = -1;
        for (int i = 0; i < layerCount; ++i) {
            const TexturePtr& t = own[std::size_t(i)][std::size_t(k)];
            plan.textures[std::size_t(i)] = t;
            if (t && (smallest < 0 || t->width() < own[std::size_t(smallest)][std::size_t(k)]->width())) smallest = i;
        }
        if (smallest < 0) continue; // every layer takes the stand-in as it is
        const Texture& reference = *own[std::size_t(smallest)][std::size_t(k)];
        plan.width = reference.width();
        plan.height = reference.height();
        plan.levels = reference.levels.size();
        // Where each present map reaches that size, and how many levels all share from there.
        for (int i = 0; i < layerCount; ++i) {
            const TexturePtr& t = own[std::size_t(i)][std::size_t(k)];
            if (!t) continue;
            const std::string what = "material: layer '" + layerName(material, i) + "' map " + SLOT_NAMES[k];
            if (t->srgb != reference.srgb) {
                throw Error(ErrorKind::BadInput, what + " is " + (t->srgb ? "sRGB" : "linear") + " but layer '" +
                            layerName(material, smallest) + "''s is not (one colour space per map slot)");
            }
            std::size_t j = 0;
            while (j < t->levels.size() && !(t->levels[j].width == plan.width && t->levels[j].height == plan.height)) ++j;
            if (j == t->levels.size()) {
                throw Error(ErrorKind::BadInput, what + " is " + size(t->width(), t->height()) + ": none of its mip levels is " +
                            size(plan.width, plan.height) + ", the size of layer '" + layerName(material, smallest) +
                            "''s (the layers' maps of one slot share a texture array: give them one size, or sizes a "
                            "power of two apart)");
            }
            plan.first[std::size_t(i)] = j;
            plan.levels = std::min(plan.levels, t->levels.size() - j);
        }
    }
    return plans;
}

LayerMaps resolveLayerMaps(const Material& material)
{
    LayerMaps out;
    out.layerCount = 1 + int(material.layers.size());
    const std::array<SlotPlan, 9> plans = planLayerSlots(material);
    for (int k = 0; k < 9; ++k) {
        const SlotPlan& plan = plans[std::size_t(k)];
        std::vector<TexturePtr>& slot = out.slots[std::size_t(k)];
        if (plan.levels == 0) {
            slot.assign(std::size_t(out.layerCount), standIn(k));
            continue;
        }
        for (int i = 0; i < out.layerCount; ++i) {
            const TexturePtr& t = plan.textures[std::size_t(i)];
            if (!t) {
                slot.push_back(derivedTextures().get(standIn(k), 0, plan.width, plan.height, plan.levels, [&] {
                    return constantLevels(*standIn(k), plan.width, plan.height, plan.levels);
                }));
            } else if (plan.first[std::size_t(i)] == 0 && t->levels.size() == plan.levels) {
                slot.push_back(t);
            } else {
                const std::size_t first = plan.first[std::size_t(i)];
                slot.push_back(derivedTextures().get(t, first, plan.width, plan.height, plan.levels,
                                                     [&] { return levelsFrom(*t, first, plan.levels); }));
            }
        }
    }
    return out;
}

} // namespace strata::render::detail
