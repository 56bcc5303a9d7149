// Builtins.h: the registry of built-in scenes ("builtin:NAME").
#pragma once

#include <lantern/Scene.h>

#include <string_view>

namespace lantern::scene {

/// Three spheres of different materials on a plane, lit by a directional and a point light.
Scene makeSpheresScene();

/// The spheres with an animation: the lamp orbits, the middle sphere bounces (4 s loop).
Scene makeAnimatedSpheresScene();

} // namespace lantern::scene
