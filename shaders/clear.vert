// clear.vert: one triangle over the whole render area, for clearing by drawing (gpu/ClearDraw.h):
// vertices (-1, -1), (3, -1), (-1, 3) in clip space, from gl_VertexIndex alone.
#version 460

void main() {
    const vec2 corner = vec2((gl_VertexIndex & 1) * 4 - 1, (gl_VertexIndex & 2) * 2 - 1);
    gl_Position = vec4(corner, 0.0, 1.0);
}
