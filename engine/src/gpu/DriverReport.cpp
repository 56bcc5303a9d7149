// The message for a machine without a Vulkan device. The loader says only "no driver" or
// "0 devices", which leaves the user guessing; this names the manifests it could read (the
// same search the Khronos loader makes on Linux, docs/LoaderDriverInterface.md) and the two
// ways out: install lavapipe, or point the loader at a driver it does not find by itself.
#include "gpu/DriverReport.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <vector>

namespace lantern::gpu {
namespace {

namespace fs = std::filesystem;

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

std::vector<std::string> splitPaths(const std::string& list) {
    std::vector<std::string> out;
    std::stringstream in(list);
    std::string item;
    while (std::getline(in, item, ':'))
        if (!item.empty()) out.push_back(item);
    return out;
}

// The folders the loader searches when no variable overrides it, in its order.
std::vector<fs::path> standardFolders() {
    std::vector<fs::path> folders;
    const std::string home = env("HOME");
    const std::string configHome = env("XDG_CONFIG_HOME");
    if (!configHome.empty())
        folders.emplace_back(fs::path(configHome) / "vulkan/icd.d");
    else if (!home.empty())
        folders.emplace_back(fs::path(home) / ".config/vulkan/icd.d");
    const std::string configDirs = env("XDG_CONFIG_DIRS");
    for (const std::string& d : splitPaths(configDirs.empty() ? "/etc/xdg" : configDirs))
        folders.emplace_back(fs::path(d) / "vulkan/icd.d");
    folders.emplace_back("/usr/local/etc/vulkan/icd.d");
    folders.emplace_back("/etc/vulkan/icd.d");
    const std::string dataHome = env("XDG_DATA_HOME");
    if (!dataHome.empty())
        folders.emplace_back(fs::path(dataHome) / "vulkan/icd.d");
    else if (!home.empty())
        folders.emplace_back(fs::path(home) / ".local/share/vulkan/icd.d");
    const std::string dataDirs = env("XDG_DATA_DIRS");
    for (const std::string& d :
         splitPaths(dataDirs.empty() ? "/usr/local/share:/usr/share" : dataDirs))
        folders.emplace_back(fs::path(d) / "vulkan/icd.d");
    return folders;
}

// "a.json, b.json in /usr/share/vulkan/icd.d" for a folder, or "/x.json" for a file, or why
// neither: what one entry of a list of manifests holds.
std::string describeEntry(const fs::path& p) {
    std::error_code error;
    if (fs::is_regular_file(p, error)) return p.string();
    if (!fs::is_directory(p, error)) return p.string() + " does not exist";
    std::string names;
    for (const auto& e : fs::directory_iterator(p, error)) {
        if (e.path().extension() != ".json") continue;
        names += (names.empty() ? "" : ", ") + e.path().filename().string();
    }
    return names.empty() ? p.string() + " holds no .json manifest" : names + " in " + p.string();
}

std::string describeList(const std::vector<std::string>& entries) {
    std::string out;
    for (const std::string& e : entries)
        out += (out.empty() ? "" : "; ") + describeEntry(e);
    return out;
}

// The lavapipe manifest's usual path on this architecture (Debian's mesa-vulkan-drivers).
std::string lavapipeManifest() {
#if defined(__x86_64__)
    return "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
#elif defined(__aarch64__)
    return "/usr/share/vulkan/icd.d/lvp_icd.aarch64.json";
#else
    return "/usr/share/vulkan/icd.d/lvp_icd.<arch>.json";
#endif
}

} // namespace

std::string describeDriverManifests() {
    std::string out = "Driver manifests (ICDs): ";
    // VK_DRIVER_FILES (loader 1.3.207 and newer) replaces VK_ICD_FILENAMES; either replaces
    // the search of the standard folders.
    const char* overrideName = !env("VK_DRIVER_FILES").empty()    ? "VK_DRIVER_FILES"
                               : !env("VK_ICD_FILENAMES").empty() ? "VK_ICD_FILENAMES"
                                                                  : nullptr;
    if (overrideName) {
        const std::string value = env(overrideName);
        out += std::string(overrideName) + "=" + value + " (the loader reads only these): " +
               describeList(splitPaths(value));
    } else {
        std::vector<std::string> found;
        for (const fs::path& folder : standardFolders()) {
            std::error_code error;
            if (fs::is_directory(folder, error)) found.push_back(folder.string());
        }
        out += found.empty() ? "none in the standard folders (/etc/vulkan/icd.d, "
                               "/usr/share/vulkan/icd.d, /usr/local/share/vulkan/icd.d, ...)"
                             : describeList(found);
    }
    const std::string added = env("VK_ADD_DRIVER_FILES");
    if (!added.empty())
        out += "; VK_ADD_DRIVER_FILES=" + added + ": " + describeList(splitPaths(added));
    return out;
}

std::string noDeviceMessage(const std::string& found) {
    return "no Vulkan device found: " + found + ". " + describeDriverManifests() +
           ". To render without a GPU, install lavapipe, Mesa's CPU Vulkan driver: `apt "
           "install mesa-vulkan-drivers` (Debian, Ubuntu; `dnf install mesa-vulkan-drivers` on "
           "Fedora). If a driver is installed where the loader does not look, point the loader "
           "at its manifest: VK_DRIVER_FILES=" +
           lavapipeManifest() + " (VK_ICD_FILENAMES on loaders older than 1.3.207)";
}

} // namespace lantern::gpu
