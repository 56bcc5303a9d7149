// FidelityReport.h: what `lantern info --json` and `lantern render --report FILE` say of a
// scene: every feature the file uses (Scene::features), as supported, approximated (with the
// rule's name) or skipped (with why), each with the objects that use it.
#pragma once

#include <lantern/Lantern.h>

#include <nlohmann/json.hpp>

#include <optional>

namespace lantern::cli {

/// The features as JSON, in the order of docs/scene-format-support.md's table. With `shading`
/// (a render), the maps phong alone applies per texel are approximated in gouraud and flat.
nlohmann::ordered_json fidelityJson(const Scene& scene, std::optional<ShadingMode> shading);

/// The whole report: the scene, its variants and its features.
nlohmann::ordered_json sceneReport(const std::string& source, const Scene& scene,
                                   std::optional<ShadingMode> shading);

} // namespace lantern::cli
