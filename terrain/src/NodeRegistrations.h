// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Each node source registers its node types, beside their classes; the
// builtin registry (NodeRegistry.cpp) calls every one of these.

#include <memory>
#include <string>

namespace strata::terrain {

class NodeRegistry;
class NodeArgs;
class HeightfieldBase;

void registerHeightfieldNodes(NodeRegistry& registry); // Heightfield.cpp
void registerCaveNodes(NodeRegistry& registry);        // Caves.cpp
void registerTransformNodes(NodeRegistry& registry);   // Transforms.cpp
void registerCsgNodes(NodeRegistry& registry);         // Csg.cpp
void registerPrimitiveNodes(NodeRegistry& registry);   // Primitives.cpp
void registerHeightGraphNodes(NodeRegistry& registry); // HeightGraphNodes.cpp
void registerGeologyNodes(NodeRegistry& registry);     // DifferentialErosion.cpp
void registerDemNodes(NodeRegistry& registry);         // DemHeightfield.cpp

/// The height node a child key names (null for an absent optional key);
/// fails naming the key when it names a 3D node. HeightGraphNodes.cpp.
std::shared_ptr<const HeightfieldBase> heightChild(const NodeArgs& args, const std::string& key);

} // namespace strata::terrain
