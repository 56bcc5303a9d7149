// AovChannels.h: the EXR channels of an Image's AOV planes (docs/aovs.md has the names): data
// planes as 32-bit FLOAT (half has 0.5-unit spacing at depth 1000), id planes as UINT. One
// table serves the writer and the reader (io/ImageIo.cpp, which alone sees OpenEXR).
#pragma once

#include <lantern/Image.h>
#include <lantern/Result.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lantern::io {

/// One channel of a plane: its name, type, its first pixel's value and the bytes between pixels
/// (rows are `xStride * width` bytes apart).
struct AovChannel {
    std::string name;
    bool uint = false;  ///< UINT (an id plane), else FLOAT
    char* first = nullptr;
    std::size_t xStride = 0;
};

/// Refuses an image whose AOV planes are not empty or of their size, naming the plane.
Result<void> checkAovPlanes(const Image& image, const std::filesystem::path& path);

/// The channels of the planes `image` holds, to write.
std::vector<AovChannel> aovChannels(const Image& image);

/// Sizes each plane of `image` whose every channel the file holds (`has(name)`), and returns
/// their channels, to read into.
std::vector<AovChannel> aovChannelsToRead(Image& image,
                                          const std::function<bool(const char*)>& has);

} // namespace lantern::io
