// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Reading one TOML table of the scene file with checked types and ranges;
/// errors read "SOURCE:LINE: KEY ...". Shared by Scene.cpp and
/// SceneMaterial.cpp.

#include <strata/Error.h>
#include <strata/Format.h>

#include <toml++/toml.h>

#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace strata::scene {

using strata::formatNumber;

/// Reads one TOML table, checking types and ranges, and remembers which keys
/// it consumed so that `finish()` can reject unknown ones (typos).
class TableReader
{
public:
    TableReader(const toml::table* table, std::string prefix, const std::string& source)
        : mTable(table), mPrefix(std::move(prefix)), mSource(source)
    {
    }

    double number(const std::string& key, double fallback, double min, double max)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        std::optional<double> value = node->value<double>(); // also accepts integers
        if (!value || node->is_boolean()) fail(node, key, shown(node) + "must be a number");
        checkRange(node, key, *value, min, max);
        return *value;
    }

    std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t min, std::int64_t max)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        if (!node->is_integer()) fail(node, key, shown(node) + "must be an integer");
        const std::int64_t value = *node->value<std::int64_t>();
        if (value < min || value > max) {
            fail(node, key, "= " + std::to_string(value) + " is out of range [" + std::to_string(min) + ", " +
                                std::to_string(max) + "]");
        }
        return value;
    }

    bool boolean(const std::string& key, bool fallback)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        if (!node->is_boolean()) fail(node, key, shown(node) + "must be true or false");
        return *node->value<bool>();
    }

    std::optional<glm::dvec3> vec3(const std::string& key, double limit)
    {
        const toml::node* node = find(key);
        if (!node) return std::nullopt;
        const toml::array* array = node->as_array();
        if (!array || array->size() != 3) fail(node, key, shown(node) + "must be an array of three numbers [x, y, z]");
        glm::dvec3 v;
        for (int i = 0; i < 3; ++i) {
            const toml::node& element = *array->get(std::size_t(i));
            std::optional<double> value = element.value<double>();
            if (!value || element.is_boolean()) {
                fail(node, key, shown(node) + "must be an array of three numbers [x, y, z]");
            }
            checkRange(&element, key + "[" + std::to_string(i) + "]", *value, -limit, limit);
            v[i] = *value;
        }
        return v;
    }

    /// A string; absent keys read as `fallback`.
    std::string string(const std::string& key, const std::string& fallback)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        if (!node->is_string()) fail(node, key, shown(node) + "must be a string");
        return *node->value<std::string>();
    }

    /// The node of `key`, or null when absent (marks the key as used).
    const toml::node* node(const std::string& key) { return find(key); }

    /// The scene file this table comes from.
    const std::string& source() const { return mSource; }

    /// Whether `key` is present (does not mark it as used).
    bool has(const std::string& key) const { return mTable && mTable->get(key); }

    /// The keys of the table, in the document's order of toml++'s map.
    std::vector<std::string> keys() const
    {
        std::vector<std::string> out;
        if (mTable) {
            for (const auto& [key, node] : *mTable) out.emplace_back(key.str());
        }
        return out;
    }

    /// "SOURCE:LINE: " of `key`'s node (or of the table).
    std::string where(const std::string& key) const
    {
        return location(mTable ? mTable->get(key) : nullptr) + qualified(key);
    }

    /// A sub-table; absent tables read as empty.
    TableReader table(const std::string& key)
    {
        const toml::node* node = find(key);
        if (node && !node->is_table()) fail(node, key, shown(node) + "must be a table");
        return TableReader(node ? node->as_table() : nullptr, qualified(key), mSource);
    }

    /// Throws on the first key that no reader asked for.
    void finish() const
    {
        if (!mTable) return;
        for (const auto& [key, node] : *mTable) {
            if (!mUsed.count(std::string(key.str()))) {
                const std::string name = qualified(std::string(key.str()));
                throw Error(ErrorKind::BadInput, location(&node) + "unknown key '" + name + "'", place(&node, name));
            }
        }
    }

    /// "= VALUE " as the user wrote it (strings in single quotes, long
    /// values cut at 60 characters), for a message "KEY = VALUE must be ...";
    /// empty for a null node or a table.
    static std::string shown(const toml::node* node)
    {
        if (!node || node->is_table()) return {};
        std::string text;
        if (const auto* value = node->as_string()) {
            text = "'" + value->get() + "'";
        } else {
            std::ostringstream out;
            node->visit([&out](const auto& n) { out << n; });
            text = out.str();
        }
        for (char& c : text) {
            if (c == '\n' || c == '\r') c = ' ';
        }
        if (text.size() > 60) text = text.substr(0, 57) + "...";
        return "= " + text + " ";
    }

    /// shown() of `key`'s node in this table (does not mark it as used).
    std::string shown(const std::string& key) const { return shown(mTable ? mTable->get(key) : nullptr); }

    /// Throws "SOURCE:LINE: KEY WHAT"; the line is the node's, or the key's
    /// own when `node` is null, or the table's when the key is absent (a
    /// required key: the table that should hold it).
    [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& what) const
    {
        if (!node && mTable) node = mTable->get(key);
        if (!node) node = mTable;
        throw Error(ErrorKind::BadInput, location(node) + qualified(key) + " " + what, place(node, qualified(key)));
    }

private:
    const toml::node* find(const std::string& key)
    {
        mUsed.insert(key);
        return mTable ? mTable->get(key) : nullptr;
    }

    void checkRange(const toml::node* node, const std::string& key, double value, double min, double max) const
    {
        if (!std::isfinite(value)) fail(node, key, "= " + formatNumber(value) + " must be finite");
        if (value < min || value > max) {
            fail(node, key, "= " + formatNumber(value) + " is out of range [" + formatNumber(min) + ", " +
                                formatNumber(max) + "]");
        }
    }

    /// The error's place: the file, the node's line, the key and the value
    /// as TOML writes it.
    ErrorPlace place(const toml::node* node, const std::string& key) const
    {
        ErrorPlace p{mSource, 0, key, ""};
        if (node) {
            p.line = int(node->source().begin.line);
            if (const auto* value = node->as_string()) {
                p.value = value->get();
            } else if (!node->is_table()) {
                std::ostringstream text;
                node->visit([&text](const auto& n) { text << n; });
                p.value = text.str();
            }
        }
        return p;
    }

    std::string qualified(const std::string& key) const { return mPrefix.empty() ? key : mPrefix + "." + key; }

    std::string location(const toml::node* node) const
    {
        std::string where = mSource;
        if (node && node->source().begin.line > 0) {
            where += ':'; // appended piecewise: GCC 12 warns falsely (-Wrestrict) on ":" + string
            where += std::to_string(node->source().begin.line);
        }
        where += ": ";
        return where;
    }

    const toml::table* mTable;
    std::string mPrefix;
    const std::string& mSource;
    std::set<std::string> mUsed;
};

} // namespace strata::scene
