// instance.glsl: the vertex stage's transforms. A draw of one primitive reads them from its
// push constants (uniforms.glsl's DrawBlock); an instanced draw (SC_INSTANCED: one draw for
// every instance of a primitive that shares its material, variant and winding,
// render/DrawLists.cpp) reads each instance's from the frame's instance buffer, at
// gl_InstanceIndex, which counts from the draw's firstInstance. Without SC_INSTANCED the buffer
// read is removed at pipeline creation, so draws of single primitives pay nothing.
#ifndef LANTERN_INSTANCE_GLSL
#define LANTERN_INSTANCE_GLSL

#include "lighting.glsl"

struct InstanceData {
    mat4 viewFromModel;    // as DrawBlock's: camera-relative, composed in double precision
    vec4 normalMatrix[3];
};

layout(set = LANTERN_SET_FRAME, binding = LANTERN_BINDING_INSTANCES, std430) readonly buffer InstanceBlock {
    InstanceData instances[];
};

mat4 vertexViewFromModel() {
    return SC_INSTANCED ? instances[gl_InstanceIndex].viewFromModel : draw.viewFromModel;
}

mat3 vertexNormalMatrix() {
    if (!SC_INSTANCED) return drawNormalMatrix();
    const vec4 c[3] = instances[gl_InstanceIndex].normalMatrix;
    return mat3(c[0].xyz, c[1].xyz, c[2].xyz);
}

#endif
