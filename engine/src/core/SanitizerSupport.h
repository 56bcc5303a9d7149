// SanitizerSupport.h: helpers that exist only in sanitizer builds (see SanitizerSupport.cpp).
#pragma once

namespace lantern::core {

/// Keeps the Vulkan drivers and layers mapped until exit (AddressSanitizer builds only).
void pinVulkanLibraries();

} // namespace lantern::core
