// Cryptomatte.h: Cryptomatte layers (lantern/Cryptomatte.h, docs/aovs.md) from a render of the
// instance and material ids at `samples` x `samples` times the picture's size with the same
// camera: each pixel's samples are counted per name hash and ranked by coverage.
#pragma once

#include <lantern/Image.h>
#include <lantern/Options.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <string>
#include <vector>

namespace lantern::render {

/// Refuses levels that are odd or outside 2 .. 16, and samples outside 1 .. 16.
Result<void> checkCryptomatte(const AovSet& aovs);

/// The options of the supersampled id render for `options` (which asks for a Cryptomatte
/// layer): every size, view rectangle, intrinsic and point or line width times the sample
/// count, one sample per pixel, and only the instance and material planes.
RenderOptions cryptomatteRenderOptions(const RenderOptions& options);

/// The name Cryptomatte hashes for node `node` and for material `material` (the material
/// count stands for glTF's default material): the scene's name, else a stable stand-in.
std::string cryptomatteNodeName(const Scene& scene, std::size_t node);
std::string cryptomatteMaterialName(const Scene& scene, std::size_t material);

/// The layers `aovs` asks for, for a width x height picture, from `fine`: the render made
/// with cryptomatteRenderOptions (width * samples x height * samples, instance and material
/// planes).
std::vector<CryptomatteLayer> cryptomatteLayers(const Scene& scene, const AovSet& aovs,
                                                int width, int height, const Image& fine);

} // namespace lantern::render
