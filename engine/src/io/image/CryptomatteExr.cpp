// Cryptomatte layers as EXR channels and header attributes (io/CryptomatteExr.h).
#include "io/image/CryptomatteExr.h"

#include <lantern/Cryptomatte.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace lantern::io {
namespace {

constexpr const char* kRgba[4] = {"R", "G", "B", "A"};

// "{name}{pair:02}.{R,G,B,A}": the channel of rank 2 * pair (R id, G coverage) and the next.
std::string channelName(const std::string& layer, int pair, int c) {
    const std::string digits = std::to_string(pair);
    return layer + (pair < 10 ? "0" : "") + digits + "." + kRgba[c];
}

void layerChannels(CryptomatteLayer& layer, std::vector<AovChannel>& out) {
    const std::size_t stride = sizeof(float) * std::size_t(layer.levels) * 2;
    char* base = reinterpret_cast<char*>(layer.ranks.data());
    for (int pair = 0; pair < layer.levels / 2; ++pair)
        for (int c = 0; c < 4; ++c)
            out.push_back({channelName(layer.name, pair, c), false,
                           base + sizeof(float) * std::size_t(pair * 4 + c), stride});
}

std::string hex8(std::uint32_t v) {
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", unsigned(v));
    return hex;
}

} // namespace

Result<void> checkCryptomatte(const Image& image, const std::filesystem::path& path) {
    for (const CryptomatteLayer& layer : image.cryptomatte) {
        const std::size_t want = image.pixelCount() * std::size_t(layer.levels) * 2;
        if (layer.levels <= 0 || layer.levels % 2 != 0 || layer.ranks.size() != want)
            return makeError(ErrorCode::InvalidInput,
                             "Cryptomatte layer " + layer.name + " has " +
                                 std::to_string(layer.levels) + " levels and " +
                                 std::to_string(layer.ranks.size()) +
                                 " values (levels must be even and positive, values " +
                                 "width * height * levels * 2)",
                             {}, path.string());
    }
    return {};
}

void cryptomatteChannels(const Image& image, std::vector<AovChannel>& out) {
    // Only read through the channels when writing.
    for (CryptomatteLayer& layer : const_cast<Image&>(image).cryptomatte) layerChannels(layer, out);
}

std::vector<std::pair<std::string, std::string>> cryptomatteAttributes(const Image& image) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const CryptomatteLayer& layer : image.cryptomatte) {
        const std::string prefix = "cryptomatte/" + cryptomatteKey(layer.name) + "/";
        nlohmann::json manifest = nlohmann::json::object();
        for (const auto& [name, id] : layer.manifest) manifest[name] = hex8(id);
        out.emplace_back(prefix + "name", layer.name);
        out.emplace_back(prefix + "hash", "MurmurHash3_32");
        out.emplace_back(prefix + "conversion", "uint32_to_float32");
        out.emplace_back(prefix + "manifest", manifest.dump());
    }
    return out;
}

Result<std::vector<AovChannel>> cryptomatteChannelsToRead(
    Image& image, const std::vector<std::pair<std::string, std::string>>& attributes,
    const std::function<bool(const char*)>& has, const std::filesystem::path& path) {
    image.cryptomatte.clear();
    for (const auto& [key, value] : attributes) {
        if (key.rfind("cryptomatte/", 0) != 0 || key.size() < 5 ||
            key.compare(key.size() - 5, 5, "/name") != 0)
            continue;
        CryptomatteLayer layer;
        layer.name = value;
        while (true) {
            bool all = true;
            for (int c = 0; c < 4; ++c) all = all && has(channelName(value, layer.levels / 2, c).c_str());
            if (!all) break;
            layer.levels += 2;
        }
        if (layer.levels == 0) continue;
        const std::string manifestKey = key.substr(0, key.size() - 5) + "/manifest";
        for (const auto& [k, text] : attributes) {
            if (k != manifestKey) continue;
            const nlohmann::json m = nlohmann::json::parse(text, nullptr, false);
            if (!m.is_object())
                return makeError(ErrorCode::InvalidInput, "the manifest is not a JSON object", k,
                                 path.string());
            for (const auto& item : m.items()) {
                const std::string& name = item.key();
                const nlohmann::json& id = item.value();
                const std::string hex = id.is_string() ? id.get<std::string>() : std::string();
                if (hex.size() != 8 || !std::all_of(hex.begin(), hex.end(), [](char ch) {
                        return std::isxdigit(static_cast<unsigned char>(ch)) != 0;
                    }))
                    return makeError(ErrorCode::InvalidInput,
                                     "the id of \"" + name + "\" is not 8 hex digits", k,
                                     path.string());
                layer.manifest.emplace_back(name, std::uint32_t(std::stoul(hex, nullptr, 16)));
            }
        }
        layer.ranks.assign(image.pixelCount() * std::size_t(layer.levels) * 2, 0.0f);
        image.cryptomatte.push_back(std::move(layer));
    }
    std::vector<AovChannel> out;
    for (CryptomatteLayer& layer : image.cryptomatte) layerChannels(layer, out);
    return out;
}

} // namespace lantern::io
