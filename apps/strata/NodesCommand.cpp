// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata nodes`: every density node type a scene can use, with its keys,
// straight from the node registry (strata::terrain::NodeRegistry).
// `--markdown` prints the node table of docs/nodes.md, which a test keeps in step.

#include "Commands.h"

#include <strata/terrain/NodeRegistry.h>

#include <iostream>
#include <set>
#include <sstream>

namespace strata::app {

namespace {

using terrain::NodeKey;
using terrain::NodeKeyType;
using terrain::NodeRegistry;
using terrain::NodeType;

const std::set<std::string>& noiseKeyNames()
{
    static const std::set<std::string> names = {"noise", "fractal", "octaves", "lacunarity", "gain"};
    return names;
}

bool hasNoiseKeys(const NodeType& type) { return type.findKey("noise") != nullptr; }

/// "`base` 0 m, `amplitude` 55 m, ..., noise keys (gradient fbm, 6 octaves, gain 0.45)".
std::string markdownKeys(const NodeType& type)
{
    std::ostringstream out;
    bool first = true;
    for (const NodeKey& key : type.keys) {
        if (noiseKeyNames().count(key.name) || key.type == NodeKeyType::Seed) continue;
        out << (first ? "" : ", ") << '`' << key.name << '`';
        first = false;
        if (key.required) {
            out << " (" << nodeKeyTypeName(key.type) << ", required)";
        } else {
            out << ' ' << key.defaultText() << (key.unit.empty() || key.unit == "noise units" ? "" : " " + key.unit);
        }
    }
    if (hasNoiseKeys(type)) {
        out << (first ? "" : ", ") << "noise keys (" << type.findKey("noise")->defaultText() << ' '
            << type.findKey("fractal")->defaultText() << ", " << type.findKey("octaves")->defaultText()
            << " octaves, lacunarity " << type.findKey("lacunarity")->defaultText() << ", gain "
            << type.findKey("gain")->defaultText() << ')';
    }
    return out.str();
}

void printMarkdown(std::ostream& out)
{
    out << "| type | keys (defaults) | what |\n|---|---|---|\n";
    for (const NodeType* type : NodeRegistry::builtin().types()) {
        out << "| `" << type->name << "` | " << markdownKeys(*type) << " | " << type->description << " |\n";
    }
}

void printText(std::ostream& out)
{
    for (const NodeType* type : NodeRegistry::builtin().types()) {
        out << type->name << " — " << type->description << '\n';
        for (const NodeKey& key : type->keys) {
            std::string range = key.rangeText();
            out << "  " << key.name << " (" << nodeKeyTypeName(key.type) << ")  default " << key.defaultText();
            if (!key.unit.empty()) out << "  unit " << key.unit;
            if (!range.empty()) out << "  range " << range;
            out << "\n      " << key.description << '\n';
        }
        out << '\n';
    }
}

} // namespace

Command registerNodesCommand(CLI::App& app)
{
    auto markdown = std::make_shared<bool>(false);
    CLI::App* nodes = app.add_subcommand(
        "nodes", "List every density node type a scene's [terrain.nodes.NAME] table can use, with its keys: type, "
                 "default, unit, range and what it does");
    nodes->add_flag("--markdown", *markdown, "Print the node table of docs/nodes.md (Markdown) instead");
    return {nodes, [markdown]() {
                if (*markdown) {
                    printMarkdown(std::cout);
                } else {
                    printText(std::cout);
                }
                return 0;
            }};
}

} // namespace strata::app
