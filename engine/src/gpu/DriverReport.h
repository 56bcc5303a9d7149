// What to tell a user whose machine has no Vulkan device: which driver manifests (ICDs) the
// Vulkan loader could see, and how to install lavapipe and point the loader at it.
#pragma once

#include <string>

namespace lantern::gpu {

/// The driver manifests the loader reads: those named by VK_DRIVER_FILES (or VK_ICD_FILENAMES,
/// which it replaces) when set, else those in the standard folders, plus VK_ADD_DRIVER_FILES.
/// One sentence, e.g. "Driver manifests (ICDs): VK_DRIVER_FILES=/x.json (the loader reads
/// only these): /x.json does not exist".
std::string describeDriverManifests();

/// The NoDevice message: "no Vulkan device found: " + `found` (what the loader said), the
/// manifests above, and how to install lavapipe (`apt install mesa-vulkan-drivers`) and point
/// the loader at it (VK_DRIVER_FILES, VK_ICD_FILENAMES).
std::string noDeviceMessage(const std::string& found);

} // namespace lantern::gpu
