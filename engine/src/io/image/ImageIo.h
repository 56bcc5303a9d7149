// ImageIo.h: the image files' entry points inside the engine: OpenEXR written and read,
// writing by extension, and images read for comparison. The public functions of lantern/Io.h
// (api/Io.cpp) are these.
#pragma once

#include <lantern/Compare.h>
#include <lantern/FileOptions.h>
#include <lantern/Image.h>
#include <lantern/Result.h>

#include <filesystem>
#include <string>

namespace lantern::io {

Result<void> writeExr(const std::filesystem::path& path, const Image& image,
                      const ExrOptions& options);
Result<Image> readExr(const std::filesystem::path& path);
/// .exr or .png by the path's extension (anything else is InvalidInput).
Result<void> writeImage(const std::filesystem::path& path, const Image& image,
                        const ExrOptions& exrOptions);

Result<CompareImage> readCompareImage(const std::filesystem::path& path);
CompareImage toCompareImage(const Image& image, PixelEncoding encoding, std::string source);

} // namespace lantern::io
