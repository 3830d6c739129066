// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/PbrFolder.h>

#include <strata/Error.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace strata::render {

namespace {

namespace fs = std::filesystem;

// --- Names ------------------------------------------------------------------

/// The map a file is a candidate for.
enum class Role
{
    Albedo,
    Normal,
    Roughness,
    Smoothness,
    Occlusion,
    Height,
    Metallic,
    Arm,
    Ignored,
};
constexpr int ROLE_COUNT = int(Role::Ignored);

const char* roleName(Role role)
{
    switch (role) {
    case Role::Albedo:
        return "albedo";
    case Role::Normal:
        return "normal";
    case Role::Roughness:
        return "roughness";
    case Role::Smoothness:
        return "smoothness";
    case Role::Occlusion:
        return "occlusion";
    case Role::Height:
        return "height";
    case Role::Metallic:
        return "metallic";
    case Role::Arm:
        return "arm";
    case Role::Ignored:
        return "ignored";
    }
    return "ignored";
}

std::string lower(std::string text)
{
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

/// Lower-case tokens of a file stem, split at separators (anything but
/// letters and digits), camelCase ("NormalGL" → normal, gl; "AOMap" → ao,
/// map) and letter/digit boundaries ("Rock023" → rock, 023).
std::vector<std::string> tokens(const std::string& stem)
{
    std::vector<std::string> out;
    std::string current;
    auto flush = [&] {
        if (!current.empty()) out.push_back(lower(current));
        current.clear();
    };
    auto isUpper = [](char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; };
    auto isLower = [](char c) { return std::islower(static_cast<unsigned char>(c)) != 0; };
    auto isDigit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
    for (std::size_t i = 0; i < stem.size(); ++i) {
        const char c = stem[i];
        if (!isUpper(c) && !isLower(c) && !isDigit(c)) {
            flush();
            continue;
        }
        if (!current.empty()) {
            const char p = current.back();
            const bool next = i + 1 < stem.size() && isLower(stem[i + 1]);
            if ((isLower(p) && isUpper(c)) || (isDigit(p) != isDigit(c)) || (isUpper(p) && isUpper(c) && next)) {
                flush();
            }
        }
        current.push_back(c);
    }
    flush();
    return out;
}

/// What one token says about the map: a role, and for normal maps the
/// convention when the token carries it ("normalgl").
struct TokenMeaning
{
    Role role = Role::Ignored;
    int rank = 0;        ///< lower is preferred among candidates of one role
    int convention = -1; ///< −1: unsaid, 0: OpenGL, 1: DirectX
};

std::optional<TokenMeaning> tokenMeaning(const std::string& t)
{
    struct Entry
    {
        const char* token;
        Role role;
        int rank;
        int convention;
    };
    static const Entry entries[] = {
        {"color", Role::Albedo, 0, -1},
        {"colour", Role::Albedo, 0, -1},
        {"col", Role::Albedo, 0, -1},
        {"basecolor", Role::Albedo, 0, -1},
        {"basecolour", Role::Albedo, 0, -1},
        {"albedo", Role::Albedo, 0, -1},
        {"diffuse", Role::Albedo, 0, -1},
        {"diff", Role::Albedo, 0, -1},
        {"normal", Role::Normal, 0, -1},
        {"nor", Role::Normal, 0, -1},
        {"nrm", Role::Normal, 0, -1},
        {"norm", Role::Normal, 0, -1},
        {"normalgl", Role::Normal, 0, 0},
        {"normaldx", Role::Normal, 0, 1},
        {"norgl", Role::Normal, 0, 0},
        {"nordx", Role::Normal, 0, 1},
        {"roughness", Role::Roughness, 0, -1},
        {"rough", Role::Roughness, 0, -1},
        {"smoothness", Role::Smoothness, 0, -1},
        {"smooth", Role::Smoothness, 0, -1},
        {"gloss", Role::Smoothness, 0, -1},
        {"glossiness", Role::Smoothness, 0, -1},
        {"ao", Role::Occlusion, 0, -1},
        {"occlusion", Role::Occlusion, 0, -1},
        {"ambientocclusion", Role::Occlusion, 0, -1},
        {"height", Role::Height, 0, -1},
        {"displacement", Role::Height, 0, -1},
        {"disp", Role::Height, 0, -1},
        {"displ", Role::Height, 0, -1},
        {"bump", Role::Height, 1, -1},
        {"metallic", Role::Metallic, 0, -1},
        {"metalness", Role::Metallic, 0, -1},
        {"metal", Role::Metallic, 0, -1},
        {"arm", Role::Arm, 0, -1},
        {"orm", Role::Arm, 0, -1},
    };
    static const char* ignored[] = {
        "preview",      "sphere",       "cube",       "thumb",    "thumbnail", "render",    "opacity",
        "alpha",        "transparency", "mask",       "specular", "spec",      "emission",  "emissive",
        "translucency", "transmission", "scattering", "sss",      "cavity",    "curvature", "id"};
    for (const Entry& e : entries) {
        if (t == e.token) return TokenMeaning{e.role, e.rank, e.convention};
    }
    for (const char* i : ignored) {
        if (t == i) return TokenMeaning{Role::Ignored, 0, -1};
    }
    return std::nullopt;
}

bool isImageExtension(const fs::path& path)
{
    static const char* extensions[] = {".png",  ".jpg", ".jpeg", ".tga",  ".tif",
                                       ".tiff", ".exr", ".bmp",  ".webp", ".hdr"};
    const std::string ext = lower(path.extension().string());
    return std::any_of(std::begin(extensions), std::end(extensions), [&](const char* e) { return ext == e; });
}

struct Candidate
{
    fs::path path;
    int rank = 0;
    bool directX = false;
};

std::string quoted(const fs::path& path)
{
    std::string text(1, '\'');
    text += path.string();
    text += '\'';
    return text;
}

// --- Images -------------------------------------------------------------------

enum class Filter
{
    Linear, ///< plain average of the stored values
    Srgb,   ///< RGB decoded from sRGB, averaged, encoded; alpha plain
    Normal, ///< RGB decoded as a unit vector, averaged, renormalised; alpha plain
};

std::uint8_t toByte(float v)
{
    return std::uint8_t(std::clamp(std::lround(v * 255.0f), 0l, 255l));
}

float linearToSrgb(float c)
{
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

/// Halves `image` (rounding down, at least 1) with a 2×2 box (the last row
/// or column repeated where a side is odd or 1).
Image halve(const Image& image, Filter filter)
{
    Image out;
    out.width = std::max(1, image.width / 2);
    out.height = std::max(1, image.height / 2);
    out.pixels.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
    for (int y = 0; y < out.height; ++y) {
        const int y0 = std::min(2 * y, image.height - 1);
        const int y1 = std::min(2 * y + 1, image.height - 1);
        for (int x = 0; x < out.width; ++x) {
            const int x0 = std::min(2 * x, image.width - 1);
            const int x1 = std::min(2 * x + 1, image.width - 1);
            const std::uint8_t* p[4] = {image.at(x0, y0), image.at(x1, y0), image.at(x0, y1), image.at(x1, y1)};
            std::uint8_t* d = out.at(x, y);
            float alpha = 0.0f;
            for (const std::uint8_t* s : p) alpha += s[3] / 255.0f;
            d[3] = toByte(alpha * 0.25f);
            if (filter == Filter::Normal) {
                glm::vec3 n(0.0f);
                for (const std::uint8_t* s : p) {
                    n += glm::vec3(s[0], s[1], s[2]) / 127.5f - 1.0f;
                }
                const float length = glm::length(n);
                n = length > 1e-6f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
                for (int c = 0; c < 3; ++c) d[c] = toByte(n[c] * 0.5f + 0.5f);
                continue;
            }
            for (int c = 0; c < 3; ++c) {
                float sum = 0.0f;
                for (const std::uint8_t* s : p) sum += filter == Filter::Srgb ? srgbByteToLinear(s[c]) : s[c] / 255.0f;
                sum *= 0.25f;
                d[c] = toByte(filter == Filter::Srgb ? linearToSrgb(sum) : sum);
            }
        }
    }
    return out;
}

Image shrinkTo(Image image, int maxSize, Filter filter)
{
    while (maxSize > 0 && (image.width > maxSize || image.height > maxSize)) image = halve(image, filter);
    return image;
}

/// A single-channel image in R from `source`'s channel `channel`, inverted or not.
Image channelOf(const Image& source, int channel, bool invert)
{
    ChannelMapping mapping;
    mapping.channels[0] = {channel, invert};
    return remapChannels(source, mapping);
}

/// A loaded map with the file and size it came from.
struct Loaded
{
    fs::path path;
    int fileWidth = 0;
    int fileHeight = 0;
    Image image;
};

std::string sizeText(int w, int h)
{
    return std::to_string(w) + "x" + std::to_string(h);
}

} // namespace

PbrFiles findPbrFiles(const fs::path& folder, bool defaultNormalDirectX)
{
    const std::string where = "PBR folder " + quoted(folder);
    std::error_code ec;
    if (!fs::exists(folder, ec)) throw Error(ErrorKind::BadInput, where + ": no such folder");
    if (!fs::is_directory(folder, ec)) throw Error(ErrorKind::BadInput, where + ": is not a folder");

    std::vector<fs::path> files;
    fs::directory_iterator it(folder, ec);
    if (ec) throw Error(ErrorKind::Io, where + ": cannot list: " + ec.message(), ErrorPlace{folder.string()});
    for (const fs::directory_entry& entry : it) {
        const fs::path& path = entry.path();
        const std::string name = path.filename().string();
        if (name.empty() || name[0] == '.' || !isImageExtension(path)) continue;
        if (!entry.is_regular_file(ec)) continue;
        files.push_back(path);
    }
    std::sort(files.begin(), files.end());

    std::array<std::vector<Candidate>, ROLE_COUNT> candidates;
    for (const fs::path& path : files) {
        const std::vector<std::string> parts = tokens(path.stem().string());
        std::optional<TokenMeaning> meaning;
        int convention = -1;
        for (const std::string& t : parts) {
            if (const std::optional<TokenMeaning> m = tokenMeaning(t)) meaning = m;
            if (t == "gl" || t == "opengl" || t == "ogl") convention = 0;
            if (t == "dx" || t == "directx") convention = 1;
        }
        if (!meaning || meaning->role == Role::Ignored) continue;
        Candidate c{path, meaning->rank, false};
        if (meaning->role == Role::Normal) {
            if (meaning->convention >= 0) convention = meaning->convention;
            c.directX = convention < 0 ? defaultNormalDirectX : convention == 1;
            // Explicitly the default convention, then unsaid, then the other one.
            c.rank = convention < 0 ? 1 : (c.directX == defaultNormalDirectX ? 0 : 2);
        }
        candidates[std::size_t(meaning->role)].push_back(c);
    }

    auto pick = [&](Role role) -> std::optional<Candidate> {
        const std::vector<Candidate>& list = candidates[std::size_t(role)];
        if (list.empty()) return std::nullopt;
        int best = list[0].rank;
        for (const Candidate& c : list) best = std::min(best, c.rank);
        std::vector<const Candidate*> tied;
        for (const Candidate& c : list) {
            if (c.rank == best) tied.push_back(&c);
        }
        if (tied.size() > 1) {
            std::string names;
            for (const Candidate* c : tied) names += (names.empty() ? "" : ", ") + quoted(c->path.filename());
            throw Error(ErrorKind::BadInput, where + ": " + std::to_string(tied.size()) + " candidates for the " + roleName(role) +
                        " map: " + names + "; remove all but one");
        }
        return *tied[0];
    };

    PbrFiles files_;
    const std::optional<Candidate> albedo = pick(Role::Albedo);
    if (!albedo) {
        throw Error(ErrorKind::BadInput, where + ": no albedo / base colour map (a file named like *_Color.*, *_BaseColor.*, *_albedo.*, "
                            "*_diffuse.* or *_diff_*)");
    }
    files_.albedo = albedo->path;
    if (const auto c = pick(Role::Normal)) {
        files_.normal = c->path;
        files_.normalDirectX = c->directX;
    }
    if (const auto c = pick(Role::Roughness)) files_.roughness = c->path;
    if (files_.roughness.empty()) {
        if (const auto c = pick(Role::Smoothness)) files_.smoothness = c->path;
    }
    if (const auto c = pick(Role::Occlusion)) files_.occlusion = c->path;
    if (const auto c = pick(Role::Height)) files_.height = c->path;
    if (const auto c = pick(Role::Metallic)) files_.metallic = c->path;
    if (const auto c = pick(Role::Arm)) files_.arm = c->path;
    return files_;
}

PbrMaps loadPbrFolder(const fs::path& folder, const MipOptions& mips, int maxSize, bool defaultNormalDirectX)
{
    if (maxSize < 0 || (maxSize & (maxSize - 1)) != 0) {
        throw Error(ErrorKind::BadInput, "PBR folder " + quoted(folder) + ": maxSize = " + std::to_string(maxSize) +
                    " must be 0 (keep) or a power of two");
    }
    const PbrFiles files = findPbrFiles(folder, defaultNormalDirectX);
    auto load = [&](const fs::path& path, MapKind kind, int minChannels, const char* map, Filter filter) {
        Loaded l;
        l.path = path;
        l.image = loadMapImage(path, kind, minChannels, "PBR folder, " + std::string(map) + " map");
        l.fileWidth = l.image.width;
        l.fileHeight = l.image.height;
        l.image = shrinkTo(std::move(l.image), maxSize, filter);
        return l;
    };

    PbrMaps maps;
    maps.albedo =
        makeTexture(load(files.albedo, MapKind::Albedo, 1, "albedo", Filter::Srgb).image, MapKind::Albedo, mips);
    if (!files.normal.empty()) {
        Loaded normal = load(files.normal, MapKind::Normal, 3, "normal", Filter::Normal);
        if (files.normalDirectX) flipGreen(normal.image);
        maps.normal = makeTexture(normal.image, MapKind::Normal, mips);
    }

    // The MOHS parts: R of each image, with the file it came from.
    std::optional<Loaded> arm;
    if (!files.arm.empty()) arm = load(files.arm, MapKind::Mask, 3, "arm", Filter::Linear);
    struct Part
    {
        const Loaded* from = nullptr;
        Image image;
    };
    std::optional<Loaded> separate[4];
    Part parts[4]; // metallic, occlusion, height, smoothness
    auto fromFile = [&](int slot, const fs::path& path, const char* map, bool invert) {
        if (path.empty()) return false;
        separate[slot] = load(path, MapKind::Mask, 1, map, Filter::Linear);
        parts[slot] = {&*separate[slot], channelOf(separate[slot]->image, 0, invert)};
        return true;
    };
    auto fromArm = [&](int slot, int channel, bool invert) {
        if (arm) parts[slot] = {&*arm, channelOf(arm->image, channel, invert)};
    };
    if (!fromFile(0, files.metallic, "metallic", false)) fromArm(0, 2, false);
    if (!fromFile(1, files.occlusion, "occlusion", false)) fromArm(1, 0, false);
    fromFile(2, files.height, "height", false);
    if (!fromFile(3, files.roughness, "roughness", true) && !fromFile(3, files.smoothness, "smoothness", false)) {
        fromArm(3, 1, true);
    }

    const Part* first = nullptr;
    for (const Part& part : parts) {
        if (!part.from) continue;
        if (first && (part.image.width != first->image.width || part.image.height != first->image.height)) {
            throw Error(ErrorKind::BadInput, "PBR folder " + quoted(folder) +
                        ": the maps packed into the mask differ in size: " + quoted(first->from->path.filename()) +
                        " is " + sizeText(first->from->fileWidth, first->from->fileHeight) + ", " +
                        quoted(part.from->path.filename()) + " is " +
                        sizeText(part.from->fileWidth, part.from->fileHeight));
        }
        first = first ? first : &part;
    }
    if (first) {
        auto pointer = [&](int slot) { return parts[slot].from ? &parts[slot].image : nullptr; };
        maps.mask = makeTexture(packMohs(pointer(0), pointer(1), pointer(2), pointer(3)), MapKind::Mask, mips);
    }
    return maps;
}

} // namespace strata::render
