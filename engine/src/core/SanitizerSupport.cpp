// Compiled only into AddressSanitizer builds (LANTERN_SANITIZE contains "address"): keeps
// every Vulkan driver and layer library mapped until the process ends, so that LeakSanitizer,
// which looks after the loader has unloaded them, can name the library behind their one-off
// allocations (tests/lsan.supp suppresses those by library name). The fast unwinder cannot
// walk through the drivers' frames, and the slow one deadlocks against lavapipe's threads.
#include "core/SanitizerSupport.h"

#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>

namespace lantern::core {
namespace {

// The value of "library_path" in a Vulkan ICD or layer manifest ("" if absent).
std::string libraryPath(const std::string& json) {
    const std::string key = "\"library_path\"";
    auto k = json.find(key);
    if (k == std::string::npos) return {};
    auto open = json.find('"', json.find(':', k + key.size()));
    if (open == std::string::npos) return {};
    auto close = json.find('"', open + 1);
    return close == std::string::npos ? std::string() : json.substr(open + 1, close - open - 1);
}

void pinLibrariesNamedIn(const char* folder) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        std::ifstream in(entry.path());
        std::stringstream json;
        json << in.rdbuf();
        const std::string path = libraryPath(json.str());
        if (!path.empty()) dlopen(path.c_str(), RTLD_LAZY | RTLD_NODELETE);
    }
}

} // namespace

void pinVulkanLibraries() {
    static std::once_flag once;
    std::call_once(once, [] {
        pinLibrariesNamedIn("/usr/share/vulkan/icd.d");
        pinLibrariesNamedIn("/usr/share/vulkan/explicit_layer.d");
    });
}

} // namespace lantern::core
