// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridToMesh.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <fstream>

using namespace strata::meshing;

namespace {

TriangleMesh sphereMesh(const glm::dvec3& origin = glm::dvec3(0.0))
{
    openvdb::initialize();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, {0.5f, 1.0f, 1.5f}, 0.25f);
    GridToMeshOptions options;
    options.origin = origin;
    return gridToMesh(*grid, options);
}

std::size_t filesIn(const std::filesystem::path& dir)
{
    return std::size_t(std::distance(std::filesystem::directory_iterator(dir), {}));
}

} // namespace

TEST(GltfIO, GlbRoundTripIsExact)
{
    const auto dir = strata::test::freshTestDir();
    const TriangleMesh mesh = sphereMesh({10.0, 20.0, -30.0});
    writeGlb(mesh, dir / "sphere.glb");

    // A binary glTF starts with the magic "glTF" and version 2.
    std::ifstream in(dir / "sphere.glb", std::ios::binary);
    char header[8] = {};
    in.read(header, 8);
    EXPECT_EQ(std::string(header, 4), "glTF");
    EXPECT_EQ(header[4], 2);

    const TriangleMesh back = readGltf(dir / "sphere.glb");
    EXPECT_EQ(back.indices, mesh.indices);
    ASSERT_EQ(back.positions.size(), mesh.positions.size());
    ASSERT_EQ(back.normals.size(), mesh.normals.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_EQ(back.positions[i], mesh.positions[i]);
        EXPECT_EQ(back.normals[i], mesh.normals[i]);
    }
    EXPECT_EQ(back.origin, mesh.origin);
    EXPECT_EQ(filesIn(dir), 1u) << "no temporary file may be left behind";
}

TEST(GltfIO, UnwritableTargetThrowsAndLeavesNothing)
{
    const auto dir = strata::test::freshTestDir();
    try {
        writeGlb(sphereMesh(), dir / "missing-dir" / "a.glb");
        FAIL() << "expected strata::Error";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Io);
        EXPECT_EQ(e.place().file, (dir / "missing-dir" / "a.glb").string());
    }
    EXPECT_EQ(filesIn(dir), 0u);
}

TEST(GltfIO, BadFilesGiveErrorsNamingThePath)
{
    const auto dir = strata::test::freshTestDir();
    {
        std::ofstream(dir / "garbage.glb") << "this is not a glTF file";
    }
    try {
        readGltf(dir / "garbage.glb");
        FAIL() << "expected strata::Error";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("garbage.glb"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readGltf(dir / "does-not-exist.glb"), strata::Error);
}

namespace {

tinygltf::Model loadGlb(const std::filesystem::path& path)
{
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path.string())) << error;
    EXPECT_EQ(warning, "");
    return model;
}

} // namespace

// glTF's default material is fully metallic (viewers show dark metal): the
// primitive carries a neutral rough dielectric, and the mesh and node are
// named after the file or the option.
TEST(GltfIO, GlbCarriesANeutralRoughMaterialAndAName)
{
    const auto dir = strata::test::freshTestDir();
    const TriangleMesh mesh = sphereMesh({1.0, 2.0, 3.0});
    writeGlb(mesh, dir / "cave-system.glb");
    const tinygltf::Model model = loadGlb(dir / "cave-system.glb");
    ASSERT_EQ(model.materials.size(), 1u);
    const tinygltf::PbrMetallicRoughness& pbr = model.materials[0].pbrMetallicRoughness;
    EXPECT_EQ(pbr.metallicFactor, 0.0);
    EXPECT_NEAR(pbr.roughnessFactor, 0.9, 1e-12);
    ASSERT_EQ(pbr.baseColorFactor.size(), 4u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(pbr.baseColorFactor[c], 0.8, 1e-12);
    EXPECT_EQ(pbr.baseColorFactor[3], 1.0);
    EXPECT_EQ(pbr.baseColorTexture.index, -1);
    ASSERT_EQ(model.meshes.size(), 1u);
    ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
    EXPECT_EQ(model.meshes[0].primitives[0].material, 0);
    EXPECT_EQ(model.meshes[0].name, "cave-system");
    ASSERT_EQ(model.nodes.size(), 1u);
    EXPECT_EQ(model.nodes[0].name, "cave-system");
    EXPECT_EQ(model.nodes[0].mesh, 0);
    EXPECT_EQ(model.nodes[0].translation, (std::vector<double>{1.0, 2.0, 3.0}));

    GlbOptions options;
    options.name = "island";
    writeGlb(mesh, dir / "out.glb", options);
    const tinygltf::Model named = loadGlb(dir / "out.glb");
    EXPECT_EQ(named.meshes.at(0).name, "island");
    EXPECT_EQ(named.nodes.at(0).name, "island");

    // An empty mesh is a named node without mesh or material.
    writeGlb(TriangleMesh{}, dir / "empty.glb");
    const tinygltf::Model empty = loadGlb(dir / "empty.glb");
    EXPECT_TRUE(empty.meshes.empty());
    EXPECT_TRUE(empty.materials.empty());
    EXPECT_EQ(empty.nodes.at(0).name, "empty");
}

TEST(GltfIO, SurfaceLandformAndRockTravelAsUnderscoreAttributes)
{
    const auto dir = strata::test::freshTestDir();
    TriangleMesh mesh = sphereMesh();
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const float t = float(i) / float(mesh.positions.size());
        mesh.surface.emplace_back(t, 1.0f - t);
        mesh.landform.emplace_back(7.0f * t, 20.0f * t, 0.5f - t, t > 0.5f ? 1.0f : 0.0f);
        mesh.rock.emplace_back(t, float(i % 5));
    }
    writeGlb(mesh, dir / "attributes.glb");
    const tinygltf::Model model = loadGlb(dir / "attributes.glb");
    const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
    ASSERT_EQ(primitive.attributes.count(SURFACE_ATTRIBUTE), 1u);
    ASSERT_EQ(primitive.attributes.count(LANDFORM_ATTRIBUTE), 1u);
    ASSERT_EQ(primitive.attributes.count(ROCK_ATTRIBUTE), 1u);
    const tinygltf::Accessor& rock = model.accessors.at(std::size_t(primitive.attributes.at(ROCK_ATTRIBUTE)));
    EXPECT_EQ(rock.type, TINYGLTF_TYPE_VEC2);
    EXPECT_EQ(rock.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(rock.count, mesh.positions.size());
    const tinygltf::Accessor& surface = model.accessors.at(std::size_t(primitive.attributes.at(SURFACE_ATTRIBUTE)));
    EXPECT_EQ(surface.type, TINYGLTF_TYPE_VEC2);
    EXPECT_EQ(surface.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(surface.count, mesh.positions.size());
    const tinygltf::Accessor& landform = model.accessors.at(std::size_t(primitive.attributes.at(LANDFORM_ATTRIBUTE)));
    EXPECT_EQ(landform.type, TINYGLTF_TYPE_VEC4);
    EXPECT_EQ(landform.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);

    const TriangleMesh back = readGltf(dir / "attributes.glb");
    EXPECT_EQ(back.surface, mesh.surface);
    EXPECT_EQ(back.landform, mesh.landform);
    EXPECT_EQ(back.rock, mesh.rock);

    // Absent (or not one per vertex): not written, read back empty.
    mesh.surface.clear();
    mesh.landform.pop_back();
    mesh.rock.pop_back();
    writeGlb(mesh, dir / "plain.glb");
    const tinygltf::Model plain = loadGlb(dir / "plain.glb");
    EXPECT_EQ(plain.meshes.at(0).primitives.at(0).attributes.size(), 2u); // POSITION, NORMAL
    const TriangleMesh none = readGltf(dir / "plain.glb");
    EXPECT_TRUE(none.surface.empty());
    EXPECT_TRUE(none.landform.empty());
    EXPECT_TRUE(none.rock.empty());
}
