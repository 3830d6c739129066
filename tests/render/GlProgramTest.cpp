// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The GLSL compile path: errors name the shader file and line and quote the
// line; the std140 uniform blocks as the driver lays them out match the C++
// mirrors in render/src/UniformBlocks.h. Runs on EGL (llvmpipe in CI).

#include <strata/Error.h>
#include <strata/render/EglContext.h>

#include "GlProgram.h"
#include "LayerSetup.h"
#include "UniformBlocks.h"
#include <strata/shaders/EmbeddedShaders.h>

#include "TestContext.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <iostream>
#include <memory>
#include <string>
#include <utility>

namespace {

using namespace strata::render;
namespace detail = strata::render::detail;

using strata::test::createContext;

/// The assembled fragment source with STRATA_FEATURES defined, as the renderer builds it.
std::string fragmentSource(unsigned features)
{
    std::string source = strata::shaders::TERRAIN_FRAG;
    source.insert(source.find('\n') + 1, "#define STRATA_FEATURES " + std::to_string(features) + "u\n");
    return source;
}

/// Replaces the first occurrence of `line` (a whole line) after the "#line
/// N0001 N" directive of file `fileIndex` with `replacement`; returns the
/// replaced line's number in that file (1-based).
int replaceLine(std::string& source, int fileIndex, const std::string& line, const std::string& replacement)
{
    const std::string directive = "#line " + std::to_string(fileIndex * strata::shaders::SOURCE_LINE_BASE + 1) + " " +
                                  std::to_string(fileIndex) + "\n";
    const std::size_t fileStart = source.find(directive);
    EXPECT_NE(fileStart, std::string::npos) << directive;
    const std::size_t bodyStart = fileStart + directive.size();
    const std::size_t at = source.find(line + "\n", bodyStart);
    EXPECT_NE(at, std::string::npos) << line;
    if (fileStart == std::string::npos || at == std::string::npos) {
        return -1;
    }
    int number = 1;
    for (std::size_t i = bodyStart; i < at; ++i) {
        number += source[i] == '\n';
    }
    source.replace(at, line.size(), replacement);
    return number;
}

int fileIndex(const std::string& name)
{
    for (std::size_t i = 0; i < strata::shaders::SOURCE_NAME_COUNT; ++i) {
        if (name == strata::shaders::SOURCE_NAMES[i]) {
            return int(i);
        }
    }
    ADD_FAILURE() << name << " is not an embedded shader file";
    return 0;
}

std::string compileError(const std::string& source)
{
    try {
        detail::compileShader(GL_FRAGMENT_SHADER, source, "terrain fragment (test)");
    } catch (const strata::Error& e) {
        return e.what();
    }
    return "";
}

TEST(GlProgram, CompileErrorInTheFragmentShaderNamesFileLineAndSource)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    std::string source = fragmentSource(0u);
    const int line = replaceLine(source, fileIndex("terrain.frag"),
                                 "    SurfaceOutput o = evaluateSurface(s, uMaterial);",
                                 "    SurfaceOutput o = brokenOnPurpose(s);");
    ASSERT_GT(line, 10);
    const std::string message = compileError(source);
    ASSERT_FALSE(message.empty()) << "the broken shader compiled";
    std::cout << message << std::endl;
    EXPECT_NE(message.find("GLSL compile error in the terrain fragment (test) shader"), std::string::npos) << message;
    EXPECT_NE(message.find("terrain.frag:" + std::to_string(line)), std::string::npos) << message;
    EXPECT_NE(message.find("brokenOnPurpose"), std::string::npos) << message;
    EXPECT_NE(message.find("`SurfaceOutput o = brokenOnPurpose(s);`"), std::string::npos)
        << "the offending source line is not quoted: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

TEST(GlProgram, CompileErrorInTheSharedHeaderNamesThatHeader)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    std::string source = fragmentSource(1023u);
    const int line = replaceLine(source, fileIndex("TriplanarMaterial.h"), "    o.height = mask.z;",
                                 "    o.height = mask.q + undefinedHeight;");
    ASSERT_GT(line, 1);
    const std::string message = compileError(source);
    ASSERT_FALSE(message.empty());
    EXPECT_NE(message.find("TriplanarMaterial.h:" + std::to_string(line)), std::string::npos) << message;
    EXPECT_NE(message.find("`o.height = mask.q + undefinedHeight;`"), std::string::npos) << message;
}

TEST(GlProgram, LogLocationsOfBothDriverStylesAreMapped)
{
    // Mesa "string:line(column)" and NVIDIA "string(line)" locations, with
    // the source line quoted from the #line numbering of the source.
    const std::string source = "#version 450 core\n#line 50001 5\nvoid main()\n{\n    bad line here;\n}\n";
    const std::string mesa = detail::describeShaderLog("0:50003(5): error: syntax error\n", source);
    EXPECT_EQ(mesa, std::string(strata::shaders::SOURCE_NAMES[5]) + ":3(5): error: syntax error `bad line here;`");
    const std::string nvidia =
        detail::describeShaderLog("0(50003) : error C0000: syntax error\n0(50001) : warning C7050: unused\n", source);
    EXPECT_EQ(nvidia, std::string(strata::shaders::SOURCE_NAMES[5]) + "(3) : error C0000: syntax error `bad line here;`");
    EXPECT_EQ(detail::describeShaderLog("", source), "(empty log)");
    // A location beyond the files keeps its number and quotes nothing.
    EXPECT_EQ(detail::describeShaderLog("0:990001(1): error: x", source), "0:990001(1): error: x");
}

TEST(GlProgram, EmbeddedProgramsCompileAndLink)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const detail::GlObject vertex =
        detail::compileShader(GL_VERTEX_SHADER, strata::shaders::TERRAIN_VERT, "terrain vertex");
    const detail::GlObject fragment = detail::compileShader(GL_FRAGMENT_SHADER, fragmentSource(1023u), "terrain fragment");
    const detail::GlObject program = detail::linkProgram(vertex, fragment, "terrain");
    EXPECT_NE(program.id(), 0u);
    EXPECT_NO_THROW(detail::checkGl("test"));
}

/// The driver's offset of uniform `name` (a member of a uniform block).
GLint uniformOffset(GLuint program, const std::string& name)
{
    const char* names[] = {name.c_str()};
    GLuint index = GL_INVALID_INDEX;
    glGetUniformIndices(program, 1, names, &index);
    EXPECT_NE(index, GL_INVALID_INDEX) << name << " is not an active uniform";
    if (index == GL_INVALID_INDEX) {
        return -1;
    }
    GLint offset = -1;
    glGetActiveUniformsiv(program, 1, &index, GL_UNIFORM_OFFSET, &offset);
    return offset;
}

GLint blockSize(GLuint program, const char* block)
{
    const GLuint index = glGetUniformBlockIndex(program, block);
    EXPECT_NE(index, GL_INVALID_INDEX) << block;
    GLint size = -1;
    glGetActiveUniformBlockiv(program, index, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
    return size;
}

GLint blockBinding(GLuint program, const char* block)
{
    const GLuint index = glGetUniformBlockIndex(program, block);
    GLint binding = -1;
    glGetActiveUniformBlockiv(program, index, GL_UNIFORM_BLOCK_BINDING, &binding);
    return binding;
}

TEST(GlProgram, UniformBlocksMatchTheStd140MirrorsInCpp)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const detail::GlObject vertex =
        detail::compileShader(GL_VERTEX_SHADER, strata::shaders::TERRAIN_VERT, "terrain vertex");
    // Every feature but layers, and the debug views: every member is active.
    const detail::GlObject fragment =
        detail::compileShader(GL_FRAGMENT_SHADER, fragmentSource(4095u & ~1024u), "terrain fragment");
    const detail::GlObject linked = detail::linkProgram(vertex, fragment, "terrain");
    const GLuint p = linked.id();

    EXPECT_EQ(blockSize(p, "FrameBlock"), GLint(sizeof(detail::FrameBlock)));
    EXPECT_EQ(blockSize(p, "MaterialBlock"), GLint(sizeof(detail::MaterialBlock)));
    EXPECT_EQ(blockSize(p, "LightingBlock"), GLint(sizeof(detail::LightingBlock)));
    EXPECT_EQ(blockBinding(p, "FrameBlock"), GLint(detail::FRAME_BLOCK_BINDING));
    EXPECT_EQ(blockBinding(p, "MaterialBlock"), GLint(detail::MATERIAL_BLOCK_BINDING));
    EXPECT_EQ(blockBinding(p, "LightingBlock"), GLint(detail::LIGHTING_BLOCK_BINDING));

#define STRATA_EXPECT_OFFSET(glslName, Block, member) \
    EXPECT_EQ(uniformOffset(p, glslName), GLint(offsetof(detail::Block, member))) << glslName
    STRATA_EXPECT_OFFSET("FrameBlock.viewProjection", FrameBlock, viewProjection);
    STRATA_EXPECT_OFFSET("FrameBlock.cameraPosition", FrameBlock, cameraPosition);
    STRATA_EXPECT_OFFSET("FrameBlock.textureOffset", FrameBlock, textureOffset);
    STRATA_EXPECT_OFFSET("FrameBlock.wireColor", FrameBlock, wireColor);
    STRATA_EXPECT_OFFSET("FrameBlock.mapScale", FrameBlock, mapScale);
    STRATA_EXPECT_OFFSET("FrameBlock.debugView", FrameBlock, debugView);
    STRATA_EXPECT_OFFSET("FrameBlock.wireframePass", FrameBlock, wireframePass);
    STRATA_EXPECT_OFFSET("FrameBlock.detailOffset", FrameBlock, detailOffset);
    STRATA_EXPECT_OFFSET("FrameBlock.tileOffset", FrameBlock, tileOffset);

    STRATA_EXPECT_OFFSET("uMaterial.albedoTint", MaterialBlock, albedoTint);
    STRATA_EXPECT_OFFSET("uMaterial.blendOffset", MaterialBlock, blendOffset);
    STRATA_EXPECT_OFFSET("uMaterial.biplanar", MaterialBlock, biplanar);
    STRATA_EXPECT_OFFSET("uMaterial.antiTilingSharpness", MaterialBlock, antiTilingSharpness);
    STRATA_EXPECT_OFFSET("uMaterial.blendExponent", MaterialBlock, blendExponent);
    STRATA_EXPECT_OFFSET("uMaterial.heightStrength", MaterialBlock, heightStrength);
    STRATA_EXPECT_OFFSET("uMaterial.metallic", MaterialBlock, metallic);
    STRATA_EXPECT_OFFSET("uMaterial.smoothness", MaterialBlock, smoothness);
    STRATA_EXPECT_OFFSET("uMaterial.occlusionStrength", MaterialBlock, occlusionStrength);
    STRATA_EXPECT_OFFSET("uMaterial.normalStrength", MaterialBlock, normalStrength);
    STRATA_EXPECT_OFFSET("uMaterial.detailScale", MaterialBlock, detailScale);
    STRATA_EXPECT_OFFSET("uMaterial.detailAlbedo", MaterialBlock, detailAlbedo);
    STRATA_EXPECT_OFFSET("uMaterial.detailSmoothness", MaterialBlock, detailSmoothness);
    STRATA_EXPECT_OFFSET("uMaterial.detailNormalStrength", MaterialBlock, detailNormalStrength);
    STRATA_EXPECT_OFFSET("uMaterial.emissionColor", MaterialBlock, emissionColor);
    STRATA_EXPECT_OFFSET("uMaterial.fresnelStrength", MaterialBlock, fresnelStrength);

    for (int i = 0; i < STRATA_MAX_LIGHTS; ++i) {
        const std::string light = "uLighting.lights[" + std::to_string(i) + "].";
        EXPECT_EQ(uniformOffset(p, light + "direction"),
                  GLint(offsetof(detail::LightingBlock, lights) + std::size_t(i) * sizeof(detail::LightBlock) +
                        offsetof(detail::LightBlock, direction)))
            << light;
        EXPECT_EQ(uniformOffset(p, light + "color"),
                  GLint(offsetof(detail::LightingBlock, lights) + std::size_t(i) * sizeof(detail::LightBlock) +
                        offsetof(detail::LightBlock, color)))
            << light;
    }
    STRATA_EXPECT_OFFSET("uLighting.lightCount", LightingBlock, lightCount);
    STRATA_EXPECT_OFFSET("uLighting.skyAmbient", LightingBlock, skyAmbient);
    STRATA_EXPECT_OFFSET("uLighting.groundAmbient", LightingBlock, groundAmbient);
    STRATA_EXPECT_OFFSET("uLighting.exposure", LightingBlock, exposure);
#undef STRATA_EXPECT_OFFSET
}

TEST(GlProgram, TheLayerBlockMatchesItsStd140MirrorInCpp)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const detail::GlObject vertex =
        detail::compileShader(GL_VERTEX_SHADER, strata::shaders::TERRAIN_VERT, "terrain vertex");
    // Every feature, eight layers: every member of every layer is active.
    std::string source = fragmentSource(4095u);
    source.insert(source.find('\n') + 1, "#define STRATA_LAYERED 1\n#define STRATA_LAYER_COUNT 8\n");
    const detail::GlObject fragment = detail::compileShader(GL_FRAGMENT_SHADER, source, "layered terrain fragment");
    const detail::GlObject linked = detail::linkProgram(vertex, fragment, "layered terrain");
    const GLuint p = linked.id();
    EXPECT_EQ(blockSize(p, "LayerBlock"), GLint(sizeof(detail::LayerSetBlock)));
    EXPECT_EQ(blockBinding(p, "LayerBlock"), GLint(detail::LAYER_BLOCK_BINDING));
    for (int i : {0, 3, 7}) {
        const std::string layer = "uLayerSet.layers[" + std::to_string(i) + "].";
        const std::size_t base = offsetof(detail::LayerSetBlock, layers) + std::size_t(i) * sizeof(strata::shading::LayerParams);
        EXPECT_EQ(uniformOffset(p, layer + "slope"), GLint(base + offsetof(strata::shading::LayerParams, slope))) << layer;
        for (const auto& [name, offset] : {std::pair{"flow", offsetof(strata::shading::LayerParams, flow)},
                                           std::pair{"wear", offsetof(strata::shading::LayerParams, wear)},
                                           std::pair{"deposition", offsetof(strata::shading::LayerParams, deposition)},
                                           std::pair{"water", offsetof(strata::shading::LayerParams, water)},
                                           std::pair{"hardness", offsetof(strata::shading::LayerParams, hardness)},
                                           std::pair{"bed", offsetof(strata::shading::LayerParams, bed)},
                                           std::pair{"noise", offsetof(strata::shading::LayerParams, noise)}}) {
            EXPECT_EQ(uniformOffset(p, layer + name), GLint(base + offset)) << layer << name;
        }
        EXPECT_EQ(uniformOffset(p, layer + "tileOffset"), GLint(base + offsetof(strata::shading::LayerParams, tileOffset)))
            << layer;
        EXPECT_EQ(uniformOffset(p, layer + "mapScale"), GLint(base + offsetof(strata::shading::LayerParams, mapScale)))
            << layer;
        EXPECT_EQ(uniformOffset(p, layer + "seed"), GLint(base + offsetof(strata::shading::LayerParams, seed))) << layer;
        const std::string material = "uLayerSet.materials[" + std::to_string(i) + "].";
        const std::size_t mbase = offsetof(detail::LayerSetBlock, materials) + std::size_t(i) * sizeof(detail::MaterialBlock);
        EXPECT_EQ(uniformOffset(p, material + "emissionColor"),
                  GLint(mbase + offsetof(detail::MaterialBlock, emissionColor)))
            << material;
        EXPECT_EQ(uniformOffset(p, material + "fresnelStrength"),
                  GLint(mbase + offsetof(detail::MaterialBlock, fresnelStrength)))
            << material;
    }
    EXPECT_EQ(uniformOffset(p, "uLayerSet.count"), GLint(offsetof(detail::LayerSetBlock, count)));
    EXPECT_EQ(uniformOffset(p, "uLayerSet.blendDepth"), GLint(offsetof(detail::LayerSetBlock, blendDepth)));
}

} // namespace
