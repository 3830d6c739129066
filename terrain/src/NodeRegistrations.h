#pragma once
// Each node source registers its node types, beside their classes; the
// builtin registry (NodeRegistry.cpp) calls every one of these.

namespace strata::terrain {

class NodeRegistry;

void registerHeightfieldNodes(NodeRegistry& registry); // Heightfield.cpp
void registerCaveNodes(NodeRegistry& registry);        // Caves.cpp
void registerTransformNodes(NodeRegistry& registry);   // Transforms.cpp
void registerCsgNodes(NodeRegistry& registry);         // Csg.cpp
void registerPrimitiveNodes(NodeRegistry& registry);   // Primitives.cpp

} // namespace strata::terrain
