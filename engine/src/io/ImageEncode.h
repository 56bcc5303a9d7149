// The bytes a PNG holds for an Image: shared by writePng and toCompareImage, so that a render
// compared with a PNG reference is quantised exactly as `lantern render -o x.png` writes it.
#pragma once

#include <lantern/Image.h>

#include <vector>

namespace lantern::io {

/// 8-bit RGBA, un-premultiplied, clamped to [0,1], sRGB-encoded (non-finite values read as 0).
std::vector<unsigned char> pngPixels(const Image& image);

} // namespace lantern::io
