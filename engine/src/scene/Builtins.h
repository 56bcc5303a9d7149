// Builtins.h: the registry of built-in scenes ("builtin:NAME").
#pragma once

#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <string>
#include <string_view>
#include <vector>

namespace lantern::scene {

/// The names of the built-in scenes, and one by name (without the "builtin:" prefix).
std::vector<std::string> builtinSceneNames();
Result<Scene> builtinScene(std::string_view name);

/// Three spheres of different materials on a plane, lit by a directional and a point light.
Scene makeSpheresScene();

/// The spheres with an animation: the lamp orbits, the middle sphere bounces (4 s loop).
Scene makeAnimatedSpheresScene();

/// The OpenGL Red Book's teapots example: 24 teapots in a 4 x 6 grid, one per classic
/// material, one directional light, orthographic view (builtin:teapots and builtin:default).
Scene makeTeapotsScene();

/// One gold teapot lit as in the Red Book example, seen in perspective (builtin:teapot).
Scene makeTeapotScene();

} // namespace lantern::scene
