// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Helpers shared by the World tests.

#include <strata/meshing/MeshMetrics.h>
#include <strata/world/World.h>

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <memory>

namespace strata::test {

using MeshMap = std::map<world::ChunkKey, std::shared_ptr<const world::ChunkMeshData>>;

/// A small world for tests: 0.5 m voxels, 8 m chunks at level 0, 3 levels,
/// 2 threads.
inline world::WorldOptions smallWorldOptions(double viewRadius)
{
    world::WorldOptions o;
    o.voxelSize = 0.5;
    o.chunkSize = 16;
    o.levels = 3;
    o.lodDistance = 28.0;
    o.viewRadius = viewRadius;
    o.threads = 2;
    return o;
}

/// The current meshes of all resident chunks (after waitIdle()).
inline MeshMap currentMeshes(const world::World& w)
{
    MeshMap out;
    for (const world::ChunkKey& key : w.residentChunks()) out[key] = w.chunkMesh(key);
    return out;
}

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b)
{
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline bool sameMesh(const world::ChunkMeshData* a, const world::ChunkMeshData* b)
{
    if (!a || !b) return a == b;
    return a->key == b->key && a->mesh.origin == b->mesh.origin && sameBytes(a->mesh.positions, b->mesh.positions) &&
           sameBytes(a->mesh.normals, b->mesh.normals) && sameBytes(a->mesh.indices, b->mesh.indices) &&
           sameBytes(a->vertexCells, b->vertexCells);
}

/// Keys whose meshes differ between two snapshots of the same resident set.
inline std::vector<world::ChunkKey> differingChunks(const MeshMap& a, const MeshMap& b)
{
    std::vector<world::ChunkKey> out;
    for (const auto& [key, mesh] : a) {
        const auto it = b.find(key);
        if (it == b.end() || !sameMesh(mesh.get(), it->second.get())) out.push_back(key);
    }
    for (const auto& [key, mesh] : b)
        if (!a.count(key)) out.push_back(key);
    return out;
}

/// All chunk meshes welded into one by VertexCell (world positions, origin 0).
inline meshing::TriangleMesh weld(const MeshMap& meshes, std::map<std::size_t, int>* vertexLevels = nullptr)
{
    meshing::TriangleMesh out;
    std::map<world::VertexCell, std::uint32_t> ids;
    for (const auto& [key, data] : meshes) {
        if (!data) continue;
        std::vector<std::uint32_t> remap(data->mesh.positions.size());
        for (std::size_t i = 0; i < remap.size(); ++i) {
            const auto [it, inserted] = ids.emplace(data->vertexCells[i], std::uint32_t(out.positions.size()));
            if (inserted) {
                const glm::dvec3 p = data->mesh.origin + glm::dvec3(data->mesh.positions[i]);
                out.positions.emplace_back(glm::vec3(p));
                if (vertexLevels) (*vertexLevels)[out.positions.size() - 1] = data->vertexCells[i].level;
            }
            remap[i] = it->second;
        }
        for (std::uint32_t index : data->mesh.indices) out.indices.push_back(remap[index]);
    }
    return out;
}

} // namespace strata::test
