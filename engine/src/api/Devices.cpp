// The public device queries of lantern/Renderer.h, answered by gpu/ (DeviceSelection.cpp).
#include <lantern/Renderer.h>

#include "gpu/Device.h"

namespace lantern {

Result<DeviceList> listDevices(const std::string& deviceName) {
    return gpu::listDevices(deviceName);
}

std::string vulkanLoaderVersion() { return gpu::vulkanLoaderVersion(); }

} // namespace lantern
