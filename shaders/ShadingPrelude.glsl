// GLSL prelude of the shared shading headers: what GLSL lacks for code that
// must also compile as C++ (see ShadingPrelude.h for the C++ side).
// Embedded right after "#version 450 core" in every Strata shader.

#define STRATA_GLSL 1
#define STRATA_INLINE
#define INOUT(T) inout T
#define saturate(x) clamp((x), 0.0f, 1.0f)
