// Builtins.h: the registry of built-in scenes ("builtin:NAME").
#pragma once

#include <lantern/Scene.h>

#include <string_view>

namespace lantern::scene {

/// Three spheres of different materials on a plane, lit by a directional and a point light.
Scene makeSpheresScene();

} // namespace lantern::scene
