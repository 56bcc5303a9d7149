// CryptomatteExr.h: the EXR form of an Image's Cryptomatte layers (Cryptomatte specification
// 1.2.0): FLOAT channels {name}00.R/G/B/A, {name}01..., two ranks of (id, coverage) each, and
// the header attributes cryptomatte/<key>/name, hash, conversion and manifest. io/ImageIo.cpp
// writes and reads them with the AOV channels (io/AovChannels.h).
#pragma once

#include "io/image/AovChannels.h"

#include <lantern/Image.h>
#include <lantern/Result.h>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace lantern::io {

/// Refuses a layer whose levels are odd or not positive, or whose ranks are not of its size.
Result<void> checkCryptomatte(const Image& image, const std::filesystem::path& path);

/// The channels of every layer of `image`, to write (appended to `out`).
void cryptomatteChannels(const Image& image, std::vector<AovChannel>& out);

/// The string attributes of every layer of `image`: cryptomatte/<key>/name, hash, conversion
/// and manifest (a JSON object of name: 8 hex digits of the id's bits).
std::vector<std::pair<std::string, std::string>> cryptomatteAttributes(const Image& image);

/// The layers a file's string attributes name, with every pair of ranks whose channels the file
/// holds (`has(name)`), sized in `image` with their manifests; returns their channels to read.
/// A manifest that is not a JSON object of hex strings is refused, naming the layer.
Result<std::vector<AovChannel>> cryptomatteChannelsToRead(
    Image& image, const std::vector<std::pair<std::string, std::string>>& attributes,
    const std::function<bool(const char*)>& has, const std::filesystem::path& path);

} // namespace lantern::io
