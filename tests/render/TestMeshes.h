// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Small meshes built in the tests, counter-clockwise seen from outside.

#include <strata/render/MeshView.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace strata::test {

struct TestMesh
{
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<std::uint32_t> indices;

    render::MeshView view() const
    {
        render::MeshView v;
        v.positions = positions.data();
        v.normals = normals.data();
        v.vertexCount = positions.size();
        v.indices = indices.data();
        v.indexCount = indices.size();
        return v;
    }
};

/// An axis-aligned box with flat-shaded faces (24 vertices, 12 triangles).
inline TestMesh makeBox(const glm::vec3& lo, const glm::vec3& hi)
{
    TestMesh mesh;
    const glm::vec3 c = 0.5f * (lo + hi);
    const glm::vec3 h = 0.5f * (hi - lo);
    // Normal, then tangents a, b with a × b = normal.
    const glm::vec3 X{1, 0, 0}, Y{0, 1, 0}, Z{0, 0, 1};
    const glm::vec3 faces[6][3] = {{X, Y, Z}, {-X, Z, Y}, {Y, Z, X}, {-Y, X, Z}, {Z, X, Y}, {-Z, Y, X}};
    for (const auto& f : faces) {
        const auto base = std::uint32_t(mesh.positions.size());
        const glm::vec3 n = f[0];
        const glm::vec3 a = f[1];
        const glm::vec3 b = f[2];
        const float signs[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const auto& s : signs) {
            mesh.positions.push_back(c + (n + a * s[0] + b * s[1]) * h);
            mesh.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) {
            mesh.indices.push_back(base + i);
        }
    }
    return mesh;
}

/// A UV sphere with smooth normals: (rings + 1)·(segments + 1) vertices,
/// 2·rings·segments triangles (some degenerate at the poles).
inline TestMesh makeUvSphere(const glm::vec3& centre, float radius, int segments, int rings)
{
    TestMesh mesh;
    const float pi = 3.14159265358979f;
    for (int i = 0; i <= rings; ++i) {
        const float theta = pi * float(i) / float(rings);
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * pi * float(j) / float(segments);
            const glm::vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
            mesh.positions.push_back(centre + radius * n);
            mesh.normals.push_back(n);
        }
    }
    const auto stride = std::uint32_t(segments + 1);
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i) * stride + std::uint32_t(j);
            const std::uint32_t b = a + 1;
            const std::uint32_t c = a + stride;
            const std::uint32_t d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
        }
    }
    return mesh;
}

} // namespace strata::test
