// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// GLSL prelude of the shared shading headers: what GLSL lacks for code that
// must also compile as C++ (see ShadingPrelude.h for the C++ side).
// Embedded right after "#version 450 core" in every Strata shader.

#define STRATA_GLSL 1
#define STRATA_INLINE
#define INOUT(T) inout T
#define saturate(x) clamp((x), 0.0f, 1.0f)
// Feature-set functions: STRATA_FEATURES is #defined (e.g. 13u) before this
// prelude; feature tests are constant conditions the compiler folds away.
#define STRATA_FEATURE_FUNCTION
#define STRATA_FEATURE_ARGS
#define STRATA_MAPS_PARAM
#define STRATA_MAPS_ARG
#ifdef STRATA_LAYERED
// Layered programs (TerrainLayers.h): STRATA_FEATURES is the union of the
// layers' sets; the layer being evaluated and its own set are globals that
// sampleMap() and the feature tests read.
int gLayer = 0;
uint gLayerFeatures = 0u;
#define STRATA_IF_FEATURE(f) if ((STRATA_FEATURES & (f)) != 0u && (gLayerFeatures & (f)) != 0u)
#define STRATA_FEATURE_BITS (STRATA_FEATURES & gLayerFeatures)
#define STRATA_SELECT_LAYER(i, f) gLayer = (i); gLayerFeatures = (f)
#else
#define STRATA_IF_FEATURE(f) if ((STRATA_FEATURES & (f)) != 0u)
#define STRATA_FEATURE_BITS STRATA_FEATURES
#define STRATA_SELECT_LAYER(i, f)
#endif
#define STRATA_LAYERS_PARAM
#define LAYER_SET uLayerSet
#define SAMPLE_MAP(map, uv, dUVdx, dUVdy) sampleMap(map, uv, dUVdx, dUVdy)
