// debug.frag: the display overlays' constant colour (opaque, linear).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "lantern_shared.h"

layout(location = 0) in vec3 vColor;
layout(location = LANTERN_OUT_COLOR) out vec4 outColor;

void main() { outColor = vec4(vColor, 1.0); }
