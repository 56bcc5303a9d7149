// TextureDecode.h: an encoded image (PNG, JPEG, WebP: io/image/ImageDecode.h) decoded into a scene
// texture, for every scene format (glTF's images, an MTL's maps): the size read from the
// header and checked before a pixel is decoded, the decoder's memory charged to the load's
// budget, the error naming the file and the object.
#pragma once

#include "io/LoadDiagnostics.h"

#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace lantern::io {

/// Largest texture side accepted (Vulkan guarantees 4096; lavapipe and desktop GPUs 16384).
inline constexpr int kMaxTextureSide = 16384;

/// Decodes `size` bytes of an encoded image into an RGBA8 texture, top row first (sRGB, linear
/// filtering, repeat: the caller sets name, encoding and sampler). Refused, naming `object`:
/// bytes io::inspectImage or decodeRgba8 refuse (empty, truncated, not an image), a side outside 1 to kMaxTextureSide, a decoded image larger
/// than `maxBytes` (--max-size) or than what is left of the load's budget (charged from the
/// header, before decoding). `fileChannels`, when given, is set
/// to the channels the file holds (1 grey, 2 grey and alpha, 3 RGB, 4 RGBA).
Result<Texture> decodeTexture(const unsigned char* bytes, std::size_t size,
                              const std::string& object, std::uint64_t maxBytes,
                              const Diagnostics& diag, int* fileChannels = nullptr);

} // namespace lantern::io
