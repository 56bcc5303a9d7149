// shadow.vert: the depth-only pass that renders a shadow map (gpu/Shadows.cpp). The frame block
// bound for the pass holds the map's clip-from-view (frame/Shadows.cpp), so the draw's own
// transforms (push constants, or its instance's) carry the vertex into the light's clip space.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "instance.glsl"

layout(location = LANTERN_LOC_POSITION) in vec3 inPosition;

void main() {
    gl_Position = frame.clipFromView * (vertexViewFromModel() * vec4(inPosition, 1.0));
}
