// specialization.glsl: the feature switches of a pipeline variant. The renderer sets them to
// what the scene uses, so code for absent features is removed at pipeline creation (measured on
// lavapipe: a never-taken branch costs 2.3x more behind a uniform than behind a constant).
// Each constant has a literal default (a constant initialised from another can be folded into
// invalid SPIR-V: shaderc issue 1497). The defaults are the all-features variant.
#ifndef LANTERN_SPECIALIZATION_GLSL
#define LANTERN_SPECIALIZATION_GLSL

#include "lantern_shared.h"

layout(constant_id = LANTERN_SC_LIGHT_TYPES) const uint SC_LIGHT_TYPES = 7u;
layout(constant_id = LANTERN_SC_GL_ATTENUATION) const bool SC_GL_ATTENUATION = true;
layout(constant_id = LANTERN_SC_GL_SPOT) const bool SC_GL_SPOT = true;
layout(constant_id = LANTERN_SC_GLTF_FALLOFF) const bool SC_GLTF_FALLOFF = true;
layout(constant_id = LANTERN_SC_SPECULAR) const uint SC_SPECULAR = 1u;
layout(constant_id = LANTERN_SC_LOCAL_VIEWER) const bool SC_LOCAL_VIEWER = true;
layout(constant_id = LANTERN_SC_TWO_SIDED) const bool SC_TWO_SIDED = true;
layout(constant_id = LANTERN_SC_VERTEX_COLOR) const bool SC_VERTEX_COLOR = true;
layout(constant_id = LANTERN_SC_TEXTURE) const bool SC_TEXTURE = true;
layout(constant_id = LANTERN_SC_ALPHA_MASK) const bool SC_ALPHA_MASK = true;
layout(constant_id = LANTERN_SC_CLAMP) const uint SC_CLAMP = 0u;
layout(constant_id = LANTERN_SC_UNLIT) const bool SC_UNLIT = false;
layout(constant_id = LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE) const bool SC_AMBIENT_FOLLOWS_DIFFUSE = false;
layout(constant_id = LANTERN_SC_OPAQUE) const bool SC_OPAQUE = true;
layout(constant_id = LANTERN_SC_MAPS) const uint SC_MAPS = 255u;
layout(constant_id = LANTERN_SC_UNROLLED_LIGHTS) const uint SC_UNROLLED_LIGHTS = 0u;
layout(constant_id = LANTERN_SC_LIGHT_KINDS) const uint SC_LIGHT_KINDS = 0u;
layout(constant_id = LANTERN_SC_LIGHTS_UNIFORM) const bool SC_LIGHTS_UNIFORM = false;
layout(constant_id = LANTERN_SC_INSTANCED) const bool SC_INSTANCED = false;
layout(constant_id = LANTERN_SC_SHADOWS) const uint SC_SHADOWS = 0u;

#endif
