// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: what the mesh readers share: reading a whole file with checks,
// splitting text into lines and tokens, parsing numbers strictly, and
// BadInput errors that name the file, the line and the element.

#include <strata/Error.h>

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace strata::meshing::detail {

/// Throws a BadInput strata::Error "<name>[:line N]: <what>".
[[noreturn]] inline void failRead(const std::string& name, int line, const std::string& what)
{
    std::string message = name;
    if (line > 0) message += ":" + std::to_string(line);
    message += ": " + what;
    throw Error(ErrorKind::BadInput, message, {.file = name, .line = line});
}

/// Quotes at most 40 characters of a token for a message.
inline std::string quoted(std::string_view token)
{
    std::string text(token.substr(0, 40));
    for (char& c : text) {
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    }
    return "'" + text + (token.size() > 40 ? "...'" : "'");
}

/// The whole content of a regular file. Throws BadInput if it does not exist
/// or is not a regular file (a FIFO or a device would block or never end),
/// Io if it cannot be read.
inline std::string readWholeFile(const std::filesystem::path& path)
{
    const std::string name = path.string();
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) failRead(name, 0, "mesh file does not exist");
    if (!std::filesystem::is_regular_file(status)) failRead(name, 0, "not a regular file");
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw Error(ErrorKind::Io, name + ": cannot open: " + std::strerror(errno), {.file = name});
    std::string bytes;
    char buffer[1 << 16];
    std::size_t got = 0;
    while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) bytes.append(buffer, got);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) throw Error(ErrorKind::Io, name + ": read failed", {.file = name});
    return bytes;
}

/// A finite float from a token, or nullopt-like false. Accepts what
/// std::from_chars accepts for general floats (no leading '+', which we skip).
inline bool parseFiniteFloat(std::string_view token, float& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double d = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), d);
    if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(d) ||
        std::abs(d) > 3.4028234663852886e38) {
        return false;
    }
    value = float(d);
    return true;
}

/// An integer from a token (the whole token must be the integer).
inline bool parseInteger(std::string_view token, std::int64_t& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    return ec == std::errc() && end == token.data() + token.size() && !token.empty();
}

/// Splits text into lines and whitespace-separated tokens, keeping line
/// numbers for messages. `comment` starts a comment to the end of the line
/// ('\0' for none).
class LineReader
{
public:
    LineReader(std::string_view text, char comment)
        : mText(text), mComment(comment)
    {
    }

    /// Moves to the next line that has a token; false at the end of the text.
    bool next()
    {
        while (mPos < mText.size()) {
            const std::size_t end = std::min(mText.find('\n', mPos), mText.size());
            std::string_view line = mText.substr(mPos, end - mPos);
            mPos = end + 1;
            ++mLine;
            if (mComment) line = line.substr(0, std::min(line.find(mComment), line.size()));
            split(line);
            if (!mTokens.empty()) return true;
        }
        return false;
    }

    const std::vector<std::string_view>& tokens() const { return mTokens; }
    int line() const { return mLine; }
    /// Byte offset just past the current line.
    std::size_t offset() const { return std::min(mPos, mText.size()); }

private:
    void split(std::string_view line)
    {
        mTokens.clear();
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && isSpace(line[i])) ++i;
            const std::size_t start = i;
            while (i < line.size() && !isSpace(line[i])) ++i;
            if (i > start) mTokens.push_back(line.substr(start, i - start));
        }
    }
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

    std::string_view mText;
    char mComment;
    std::size_t mPos = 0;
    int mLine = 0;
    std::vector<std::string_view> mTokens;
};

} // namespace strata::meshing::detail
