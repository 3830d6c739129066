# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Writes the web viewer's GLSL ES 3.00 programs, generated from the same
# shared sources in shaders/ that EmbedShaders.cmake embeds into the GL
# renderer, as a JavaScript module (import "strata:shaders" in web/src).
# Run as a script:
#   cmake -DOUTPUT=<strata-shaders.js> -DSOURCE_DIR=<shaders dir> -P GenerateShaders.cmake
#
# The programs are assembled in the same order as EmbedShaders.cmake's, with
# the differences WebGL 2 needs, applied to the text here (never to a kept
# copy):
#   - no #version line (three.js writes "#version 300 es" and the material's
#     defines, STRATA_FEATURES and STRATA_LAYERED/STRATA_LAYER_COUNT, before
#     the source), then precision qualifiers and "#define STRATA_GLSL_ES 1";
#   - std140 uniform blocks with binding points (GLSL ES 3.00 has no
#     binding qualifier, and three.js sets plain uniforms) become plain
#     uniforms of the same struct: "uniform MaterialParams uMaterial;", and
#     the FrameBlock's members a struct FrameBlock with "uniform FrameBlock
#     uFrame;", so the shared code reads them by the same names;
#   - sampler binding qualifiers are dropped (the viewer sets the units);
#   - terrain.vert's attributes become three.js's `position` and `normal`,
#     moved by three.js's `modelMatrix` (a tile's placement, its
#     quantization) into the world frame, relative to uWorldOrigin; the mesh
#     attributes the bake's tiles do not carry (cavity, cover, landform) are
#     the zeros the GL renderer sets for absent attributes;
#   - the terrain and sky fragment programs end with the sRGB encoding
#     (linearToSrgb() of TriplanarShading.h), which the GL renderer leaves
#     to its sRGB framebuffer: main() becomes strataMain(), called by a
#     main() that encodes fragColor.
# #line directives number each file as EmbedShaders.cmake does (file N from
# N·10000 + 1), so a WebGL compile error names the shared file and line.

if(NOT OUTPUT OR NOT SOURCE_DIR)
  message(FATAL_ERROR "GenerateShaders.cmake: set OUTPUT and SOURCE_DIR")
endif()

set(_names ShadingPrelude.glsl TriplanarShading.h TriplanarMaterial.h TerrainFrame.glsl terrain.vert terrain.frag
  Shadow.h shadow_depth.frag fullscreen.vert probe.frag Atmosphere.h sky.frag TerrainLayers.h)
set(_line_base 10000)
set(_file_number 0)
foreach(_name IN LISTS _names)
  file(READ "${SOURCE_DIR}/${_name}" _text)
  if(NOT _text MATCHES "\n$")
    string(APPEND _text "\n")
  endif()
  string(MAKE_C_IDENTIFIER "${_name}" _id)
  math(EXPR _first_line "${_file_number} * ${_line_base} + 1")
  set(_src_${_id} "#line ${_first_line} ${_file_number}\n${_text}")
  math(EXPR _file_number "${_file_number} + 1")
endforeach()

# Checks that a rewrite matched: the web programs must not silently keep a
# construct WebGL 2 rejects when a shared source changes.
function(_rewrite variable pattern replacement what)
  set(_before "${${variable}}")
  string(REGEX REPLACE "${pattern}" "${replacement}" _after "${_before}")
  if(_after STREQUAL _before)
    message(FATAL_ERROR "GenerateShaders.cmake: no match for ${what} (pattern '${pattern}'); update the rewrite "
                        "to the shared source")
  endif()
  set(${variable} "${_after}" PARENT_SCOPE)
endfunction()

# "layout(std140, binding = N) uniform XBlock { T uName; };" -> "uniform T uName;"
set(_block_pattern "layout\\(std140, binding = [0-9]+\\) uniform [A-Za-z]+Block\n{\n    ([A-Za-z]+) (u[A-Za-z]+);\n};")
foreach(_piece terrain_frag sky_frag TerrainLayers_h)
  _rewrite(_src_${_piece} "${_block_pattern}" "uniform \\1 \\2;" "a uniform block in ${_piece}")
endforeach()
# The FrameBlock's members as a struct.
_rewrite(_src_TerrainFrame_glsl "layout\\(std140, binding = 0\\) uniform FrameBlock\n{" "struct FrameBlock\n{"
         "the FrameBlock")
_rewrite(_src_TerrainFrame_glsl "\n} uFrame;" "\n};\nuniform FrameBlock uFrame;" "the FrameBlock's instance")
# Sampler bindings.
_rewrite(_src_terrain_frag "layout\\(binding = [0-9]+\\) uniform (sampler2D(Array)?)" "uniform \\1"
         "the samplers' bindings")
# Vertex attributes: three.js's names, placed by its modelMatrix.
_rewrite(_src_terrain_vert
  "layout\\(location = 0\\) in vec3 aPosition;[^\n]*\nlayout\\(location = 1\\) in vec3 aNormal;[^\n]*\nlayout\\(location = 2\\) in vec2 aSurface;[^\n]*\nlayout\\(location = 3\\) in vec4 aLandform;[^\n]*\nlayout\\(location = 4\\) in vec2 aRock;[^\n]*\n"
  "in vec3 position; // the tile's (three.js's name)\nin vec3 normal;\nuniform mat4 modelMatrix;  // the tile's placement (three.js)\nuniform vec3 uWorldOrigin; // metres: the origin positions are relative to\n"
  "terrain.vert's attributes")
_rewrite(_src_terrain_vert "void main\\(\\)\n{\n"
  "void main()\n{\n    vec3 aPosition = (modelMatrix * vec4(position, 1.0f)).xyz - uWorldOrigin;\n    vec3 aNormal = transpose(inverse(mat3(modelMatrix))) * normal;\n    vec2 aSurface = vec2(0.0f);\n    vec4 aLandform = vec4(0.0f);\n    vec2 aRock = vec2(0.0f);\n"
  "terrain.vert's main()")
# sRGB encoding at the end of the fragment programs.
set(_encode "\nvoid main()\n{\n    strataMain();\n    fragColor = vec4(linearToSrgb(fragColor.x), linearToSrgb(fragColor.y), linearToSrgb(fragColor.z), fragColor.w);\n}\n")
foreach(_piece terrain_frag sky_frag)
  _rewrite(_src_${_piece} "\nvoid main\\(\\)\n" "\nvoid strataMain()\n" "main() in ${_piece}")
  string(APPEND _src_${_piece} "${_encode}")
endforeach()

set(_head "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp sampler2DArray;\n#define STRATA_GLSL_ES 1\n${_src_ShadingPrelude_glsl}")
set(_vert "${_head}${_src_TerrainFrame_glsl}${_src_terrain_vert}")
set(_frag "${_head}")
foreach(_piece TriplanarShading_h TriplanarMaterial_h Shadow_h Atmosphere_h TerrainLayers_h TerrainFrame_glsl terrain_frag)
  string(APPEND _frag "${_src_${_piece}}")
endforeach()
set(_fullscreen_vert "${_head}${_src_fullscreen_vert}")
set(_shadow_frag "${_head}${_src_shadow_depth_frag}")
set(_sky_frag "${_head}${_src_TriplanarShading_h}${_src_Atmosphere_h}${_src_sky_frag}")

# A JavaScript template literal: escape \, ` and ${.
function(_js_string variable out)
  set(_s "${${variable}}")
  string(REPLACE "\\" "\\\\" _s "${_s}")
  string(REPLACE "`" "\\`" _s "${_s}")
  string(REPLACE "\${" "\\\${" _s "${_s}")
  set(${out} "`${_s}`" PARENT_SCOPE)
endfunction()

set(_quoted_names "")
foreach(_name IN LISTS _names)
  if(_quoted_names)
    string(APPEND _quoted_names ", ")
  endif()
  string(APPEND _quoted_names "'${_name}'")
endforeach()

set(_out "// Generated by web/GenerateShaders.cmake from the files in shaders/. Do not edit.\n")
string(APPEND _out "/** Names of the files numbered in the #line directives (file N from N * SOURCE_LINE_BASE + 1). */\n")
string(APPEND _out "export const SOURCE_NAMES = [${_quoted_names}];\nexport const SOURCE_LINE_BASE = ${_line_base};\n")
foreach(_program vert frag fullscreen_vert sky_frag shadow_frag)
  _js_string(_${_program} _literal)
  if(_program STREQUAL "vert")
    set(_js_name TERRAIN_VERT)
  elseif(_program STREQUAL "frag")
    set(_js_name TERRAIN_FRAG)
  elseif(_program STREQUAL "shadow_frag")
    set(_js_name SHADOW_DEPTH_FRAG)
  else()
    string(TOUPPER "${_program}" _js_name)
  endif()
  string(APPEND _out "export const ${_js_name} = ${_literal};\n")
endforeach()

if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" _old)
  if(_old STREQUAL _out)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${_out}")
