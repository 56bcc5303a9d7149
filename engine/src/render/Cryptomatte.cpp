// Cryptomatte's per-pixel ranking of ids by coverage (render/Cryptomatte.h); the name hashes
// are core/Cryptomatte.cpp.
#include "render/Cryptomatte.h"

#include <lantern/Cryptomatte.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <utility>

namespace lantern::render {
namespace {

// One layer's id bits per index of the plane it is read from (kNoId: the background).
CryptomatteLayer layerFor(const char* name, int levels,
                          const std::vector<std::string>& names) {
    CryptomatteLayer layer;
    layer.name = name;
    layer.levels = levels;
    for (const std::string& n : names) layer.manifest.emplace_back(n, cryptomatteId(murmurHash3_32(n)));
    std::sort(layer.manifest.begin(), layer.manifest.end());
    layer.manifest.erase(std::unique(layer.manifest.begin(), layer.manifest.end()),
                         layer.manifest.end());
    return layer;
}

// Ranks each pixel's samples: `plane` is the fine render's index plane, `idOf` each index's id
// bits. Most coverage first, equal coverage by id bits; the background is not ranked.
void rank(const std::vector<std::uint32_t>& plane, const std::vector<std::uint32_t>& idOf,
          int width, int height, int samples, CryptomatteLayer& layer) {
    const std::size_t levels = std::size_t(layer.levels), fineWidth = std::size_t(width) * samples;
    layer.ranks.assign(std::size_t(width) * std::size_t(height) * levels * 2, 0.0f);
    const float perSample = 1.0f / float(samples * samples);
    std::vector<std::pair<std::uint32_t, int>> counts;  // (id bits, samples)
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            counts.clear();
            for (int sy = 0; sy < samples; ++sy)
                for (int sx = 0; sx < samples; ++sx) {
                    const std::uint32_t index =
                        plane[(std::size_t(y) * samples + sy) * fineWidth + std::size_t(x) * samples + sx];
                    if (index >= idOf.size()) continue;  // kNoId: the background
                    const std::uint32_t id = idOf[index];
                    auto it = std::find_if(counts.begin(), counts.end(),
                                           [&](const auto& c) { return c.first == id; });
                    if (it == counts.end()) counts.emplace_back(id, 1);
                    else ++it->second;
                }
            std::sort(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
                return a.second != b.second ? a.second > b.second : a.first < b.first;
            });
            float* out = layer.ranks.data() + (std::size_t(y) * width + x) * levels * 2;
            for (std::size_t r = 0; r < std::min(levels, counts.size()); ++r) {
                out[r * 2] = std::bit_cast<float>(counts[r].first);
                out[r * 2 + 1] = float(counts[r].second) * perSample;
            }
        }
}

} // namespace

Result<void> checkCryptomatte(const AovSet& aovs) {
    if (!aovs.anyCryptomatte()) return {};
    const int levels = aovs.cryptomatteLevels, samples = aovs.cryptomatteSamples;
    if (levels < 2 || levels > 16 || levels % 2 != 0)
        return makeError(ErrorCode::InvalidInput,
                         "Cryptomatte levels must be an even number from 2 to 16, not " +
                             std::to_string(levels),
                         "cryptomatteLevels");
    if (samples < 1 || samples > 16)
        return makeError(ErrorCode::InvalidInput,
                         "Cryptomatte samples per axis must be from 1 to 16, not " +
                             std::to_string(samples),
                         "cryptomatteSamples");
    return {};
}

RenderOptions cryptomatteRenderOptions(const RenderOptions& options) {
    const int n = options.aovs.cryptomatteSamples;
    RenderOptions o = options;
    o.width *= n;
    o.height *= n;
    o.msaa = 1;
    o.wireframe = o.normals = false;  // display overlays are not surfaces
    o.pointSize *= n;
    o.lineWidth *= n;
    o.aovs = AovSet{};
    o.aovs.instance = options.aovs.cryptoObject;
    o.aovs.material = options.aovs.cryptoMaterial;
    auto scale = [n](CameraSpec& c) {
        if (!c.intrinsics) return;
        // OpenCV puts pixel centres at integers: a pixel's n x n sub-pixels centre on it.
        Intrinsics& k = *c.intrinsics;
        k.fx *= n, k.fy *= n;
        k.cx = (k.cx + 0.5) * n - 0.5, k.cy = (k.cy + 0.5) * n - 0.5;
        k.width *= n, k.height *= n;
    };
    scale(o.camera);
    for (View& v : o.views) {
        v.x *= n, v.y *= n, v.width *= n, v.height *= n;
        scale(v.camera);
    }
    return o;
}

std::string cryptomatteNodeName(const Scene& scene, std::size_t node) {
    const std::string& name = scene.nodes[node].name;
    return name.empty() ? "node " + std::to_string(node) : name;
}

std::string cryptomatteMaterialName(const Scene& scene, std::size_t material) {
    if (material >= scene.materials.size()) return "default";
    const std::string& name = scene.materials[material].name;
    return name.empty() ? "material " + std::to_string(material) : name;
}

std::vector<CryptomatteLayer> cryptomatteLayers(const Scene& scene, const AovSet& aovs,
                                                int width, int height, const Image& fine) {
    std::vector<CryptomatteLayer> out;
    const int n = aovs.cryptomatteSamples;
    auto build = [&](const char* layerName, const std::vector<std::uint32_t>& plane,
                     std::size_t count, auto nameOf, bool nodes) {
        std::vector<std::string> names;
        std::vector<std::uint32_t> idOf;
        for (std::size_t i = 0; i < count; ++i) {
            names.push_back(nameOf(scene, i));
            idOf.push_back(cryptomatteId(murmurHash3_32(names.back())));
        }
        // The manifest names only what can be drawn: nodes with a mesh, every material.
        std::vector<std::string> listed;
        for (std::size_t i = 0; i < count; ++i)
            if (!nodes || scene.nodes[i].mesh >= 0)
                listed.push_back(names[i]);
        CryptomatteLayer layer = layerFor(layerName, aovs.cryptomatteLevels, listed);
        rank(plane, idOf, width, height, n, layer);
        out.push_back(std::move(layer));
    };
    if (aovs.cryptoObject)
        build("CryptoObject", fine.instance, scene.nodes.size(), cryptomatteNodeName, true);
    if (aovs.cryptoMaterial)
        build("CryptoMaterial", fine.material, scene.materials.size() + 1,
              cryptomatteMaterialName, false);
    return out;
}

} // namespace lantern::render
