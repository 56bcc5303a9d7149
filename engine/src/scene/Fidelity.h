// Fidelity.h: how a loader notes the features a file uses (Scene::features), by their keys in
// fidelityKeys() (lantern/Scene.h), each with the file's object that uses it.
#pragma once

#include <lantern/Scene.h>

#include <string>
#include <string_view>

namespace lantern::scene {

/// Notes that `object` uses feature `key` (a key of fidelityKeys(); anything else is a
/// programming error), with the status and rule the table gives it.
void noteFeature(Scene& scene, std::string_view key, std::string object);

/// The same with a status and rule of the loader's own (a map drawn without its texture, a
/// skipped extension named in `rule`).
void noteFeature(Scene& scene, std::string_view key, std::string object, Fidelity fidelity,
                 std::string rule);

} // namespace lantern::scene
