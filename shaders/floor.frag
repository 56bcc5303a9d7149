// floor.frag: the trivial shader of `lantern bench speed`'s floor (FeatureMode::Floor): a
// constant colour over the same pixels and geometry as a lit render (mesh.vert in front), so
// that a frame time can be given as a multiple of what rasterising alone costs.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "output.glsl"

// mesh.vert's interface, declared so that the stages match; only the AOV variant reads them.
layout(location = 0) centroid in vec3 vEyePosition;
layout(location = 1) centroid in vec3 vNormal;
layout(location = 2) centroid in vec4 vColor;
layout(location = 3) centroid in vec2 vTexcoord;

void main() {
    writeOutputs(vec3(1.0), 1.0, vNormal, vEyePosition, vTexcoord);
}
