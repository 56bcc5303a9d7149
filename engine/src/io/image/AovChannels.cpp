// The EXR channels of the AOV planes: one table of names, used to write and to read.
#include "io/image/AovChannels.h"

#include <string>

namespace lantern::io {
namespace {

// One plane: its channels (interleaved in the plane in this order) and where it lives.
struct PlaneChannels {
    const char* plane;               ///< for messages
    std::vector<const char*> names;  ///< the EXR channel names
    std::vector<float>* floats = nullptr;
    std::vector<std::uint32_t>* uints = nullptr;

    std::size_t size() const { return floats ? floats->size() : uints->size(); }
    char* data() const {
        return floats ? reinterpret_cast<char*>(floats->data())
                      : reinterpret_cast<char*>(uints->data());
    }
    void channels(std::vector<AovChannel>& out) const {
        const std::size_t stride = 4 * names.size();
        for (std::size_t c = 0; c < names.size(); ++c)
            out.push_back({names[c], uints != nullptr, data() + 4 * c, stride});
    }
};

// Every AOV plane of `image` and its channels. A const Image is only read through these.
std::vector<PlaneChannels> planes(Image& image) {
    return {
        {"depth", {"Z"}, &image.depth, nullptr},
        {"normal", {"N.X", "N.Y", "N.Z"}, &image.normal, nullptr},
        {"range", {"range"}, &image.range, nullptr},
        {"world_normal", {"Nw.X", "Nw.Y", "Nw.Z"}, &image.worldNormal, nullptr},
        {"uv", {"uv.U", "uv.V"}, &image.uv, nullptr},
        {"instance", {"id.instance"}, nullptr, &image.instance},
        {"mesh", {"id.mesh"}, nullptr, &image.mesh},
        {"primitive", {"id.primitive"}, nullptr, &image.primitive},
        {"material", {"id.material"}, nullptr, &image.material},
        {"semantic", {"id.semantic"}, nullptr, &image.semantic},
    };
}

} // namespace

Result<void> checkAovPlanes(const Image& image, const std::filesystem::path& path) {
    for (const PlaneChannels& p : planes(const_cast<Image&>(image))) {
        const std::size_t want = image.pixelCount() * p.names.size();
        if (p.size() != 0 && p.size() != want)
            return makeError(ErrorCode::InvalidInput,
                             std::string(p.plane) + " plane has " + std::to_string(p.size()) +
                                 " values, not " + std::to_string(want),
                             {}, path.string());
    }
    return {};
}

std::vector<AovChannel> aovChannels(const Image& image) {
    std::vector<AovChannel> out;
    for (const PlaneChannels& p : planes(const_cast<Image&>(image)))
        if (p.size() != 0) p.channels(out);
    return out;
}

std::vector<AovChannel> aovChannelsToRead(Image& image,
                                          const std::function<bool(const char*)>& has) {
    std::vector<AovChannel> out;
    for (PlaneChannels& p : planes(image)) {
        bool all = true;
        for (const char* name : p.names) all = all && has(name);
        if (!all) continue;
        const std::size_t n = image.pixelCount() * p.names.size();
        if (p.floats) p.floats->assign(n, 0.0f);
        else p.uints->assign(n, 0u);
        p.channels(out);
    }
    return out;
}

} // namespace lantern::io
