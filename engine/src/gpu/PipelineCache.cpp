// The pipeline cache on disk: where it lives, Lantern's file around the driver's data and the
// checks on it, reading without following links, and the careful write back.
#include "gpu/PipelineCache.h"

#include "gpu/Vk.h"

#include <lantern/Version.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <pwd.h>
#include <random>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::gpu {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'L', 'A', 'N', 'T', 'E', 'R', 'N', 'P'};
constexpr std::uint32_t kFormat = 1;
// Lantern's header: magic, format, a reserved word, then the length and checksum of the
// driver's data that follows.
constexpr std::size_t kHeaderBytes = 32;
// No driver's cache of Lantern's few dozen variants comes near this; a bigger file is refused
// rather than read into memory.
constexpr std::uint64_t kMaxFileBytes = 256ull << 20;

// FNV-1a, 64 bits: stable across compilers and runs (std::hash is neither).
std::uint64_t fnv1a(std::span<const std::uint8_t> bytes, std::uint64_t h = 14695981039346656037ull) {
    for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
    return h;
}

template <typename T>
void put(std::vector<std::uint8_t>& out, const T& value) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof value);
}

template <typename T>
T readAt(std::span<const std::uint8_t> bytes, std::size_t offset) {
    T value{};
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    return value;
}

std::string hex(std::uint64_t v, int digits) {
    char text[17];
    std::snprintf(text, sizeof text, "%0*llx", digits, static_cast<unsigned long long>(v));
    return text;
}

std::string uuidText(const std::uint8_t* uuid) {
    std::string out;
    for (std::uint32_t i = 0; i < VK_UUID_SIZE; ++i) out += hex(uuid[i], 2);
    return out;
}

std::string errnoText(int e) { return std::strerror(e); }

bool turnedOffByEnvironment() {
    const char* v = std::getenv("LANTERN_PIPELINE_CACHE");
    if (!v) return false;
    const std::string s(v);
    return s == "0" || s == "off" || s == "false" || s == "no";
}

// $LANTERN_CACHE_DIR, else $XDG_CACHE_HOME/lantern (an absolute path, as the XDG base
// directory specification requires), else ~/.cache/lantern; empty when there is no home.
fs::path cacheFolder() {
    if (const char* d = std::getenv("LANTERN_CACHE_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x == '/') return fs::path(x) / "lantern";
    const char* home = std::getenv("HOME");
    if (!home || !*home) {
        const passwd* pw = ::getpwuid(::geteuid());
        home = pw ? pw->pw_dir : nullptr;
    }
    if (!home || !*home) return {};
    return fs::path(home) / ".cache" / "lantern";
}

// Creates each missing component of `folder` with mode 0700 (the XDG rule for the cache
// home), as mkdir -p does; an error text, empty on success.
std::string makeFolder(const fs::path& folder) {
    fs::path partial;
    for (const fs::path& part : folder) {
        partial /= part;
        if (::mkdir(partial.c_str(), 0700) == 0 || errno == EEXIST) continue;
        const int e = errno;
        struct stat st {};
        if (::stat(partial.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) continue;
        return "cannot create the folder " + partial.string() + ": " + errnoText(e);
    }
    struct stat st {};
    if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        return folder.string() + " is not a folder";
    return {};
}

// What reading the file found: its bytes, or that there is none (silently), or why it was
// refused.
struct FileRead {
    bool exists = false;
    std::vector<std::uint8_t> bytes;
    std::string refused;
};

// Reads `file` without following a link at its name, and only a regular file of this user
// (a file planted in a shared folder is not handed to the driver).
FileRead readFile(const fs::path& file) {
    FileRead r;
    const int fd = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
        const int e = errno;
        if (e == ENOENT || e == ENOTDIR) return r;
        r.exists = true;
        r.refused = e == ELOOP ? "it is a symbolic link, which is not followed"
                               : "cannot be opened: " + errnoText(e);
        return r;
    }
    r.exists = true;
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
        r.refused = "it is not a regular file";
    else if (st.st_uid != ::geteuid())
        r.refused = "it belongs to another user";
    else if (std::uint64_t(st.st_size) > kMaxFileBytes)
        r.refused = "it is " + std::to_string(st.st_size) + " bytes, more than the " +
                    std::to_string(kMaxFileBytes >> 20) + " MiB a pipeline cache may be";
    if (r.refused.empty()) {
        r.bytes.resize(std::size_t(st.st_size));
        std::size_t done = 0;
        while (done < r.bytes.size()) {
            const ssize_t n = ::read(fd, r.bytes.data() + done, r.bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            done += std::size_t(n);
        }
        r.bytes.resize(done);  // a file shrunk meanwhile reads as truncated
    }
    ::close(fd);
    return r;
}

std::uint64_t randomBits() {
    std::uint64_t r = 0;
    if (::getrandom(&r, sizeof r, 0) == ssize_t(sizeof r)) return r;
    std::random_device device;
    return (std::uint64_t(device()) << 32) ^ device();
}

// Writes `bytes` to `file`: a temporary created exclusively (O_EXCL|O_NOFOLLOW, relative to
// the folder's descriptor) beside it, fsync, then rename over the name, which replaces a link
// planted there instead of following it. An error text, empty on success.
std::string writeCarefully(const fs::path& file, std::span<const std::uint8_t> bytes) {
    const int dir = ::open(file.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir < 0) return "cannot open its folder: " + errnoText(errno);
    const std::string name = file.filename().string();
    std::string temporary;
    int fd = -1;
    for (int attempt = 0; fd < 0 && attempt < 16; ++attempt) {
        temporary = "." + name + ".tmp-lantern-" + std::to_string(::getpid()) + "-" +
                    hex(randomBits(), 16);
        fd = ::openat(dir, temporary.c_str(),
                      O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd < 0 && errno != EEXIST) break;
    }
    std::string error;
    if (fd < 0) {
        error = "cannot create a temporary file in its folder: " + errnoText(errno);
        ::close(dir);
        return error;
    }
    std::size_t done = 0;
    while (error.empty() && done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) error = "write failed: " + errnoText(errno);
        else done += std::size_t(n);
    }
    if (error.empty() && ::fsync(fd) != 0) error = "fsync failed: " + errnoText(errno);
    if (::close(fd) != 0 && error.empty()) error = "close failed: " + errnoText(errno);
    if (error.empty() && ::renameat(dir, temporary.c_str(), dir, name.c_str()) != 0)
        error = "cannot rename the finished file into place: " + errnoText(errno);
    if (!error.empty()) ::unlinkat(dir, temporary.c_str(), 0);
    else ::fsync(dir);  // the rename itself reaches the disk
    ::close(dir);
    return error;
}

void warn(const LogSink& log, const fs::path& file, const std::string& what) {
    if (log) log(LogLevel::Warning, "pipeline cache " + file.string() + ": " + what);
}

// The driver's current data.
std::vector<std::uint8_t> driverData(VkDevice device, VkPipelineCache cache) {
    std::size_t size = 0;
    if (vkGetPipelineCacheData(device, cache, &size, nullptr) != VK_SUCCESS) return {};
    std::vector<std::uint8_t> data(size);
    if (size > 0 && vkGetPipelineCacheData(device, cache, &size, data.data()) < 0) return {};
    data.resize(size);
    return data;
}

} // namespace

PipelineCachePlace pipelineCachePlace(const PipelineCacheSettings& settings,
                                      const VkPhysicalDeviceProperties& props) {
    PipelineCachePlace place;
    if (!settings.onDisk) {
        place.off = "the host turned it off (RendererDesc::pipelineCacheOnDisk)";
        return place;
    }
    if (turnedOffByEnvironment()) {
        place.off = std::string("LANTERN_PIPELINE_CACHE=") + std::getenv("LANTERN_PIPELINE_CACHE");
        return place;
    }
    const fs::path folder = settings.folder.empty() ? cacheFolder() : fs::path(settings.folder);
    if (folder.empty()) {
        place.off = "no cache folder: HOME, XDG_CACHE_HOME and LANTERN_CACHE_DIR are unset";
        return place;
    }
    std::vector<std::uint8_t> key(std::begin(props.pipelineCacheUUID),
                                  std::end(props.pipelineCacheUUID));
    put(key, props.vendorID);
    put(key, props.deviceID);
    put(key, props.driverVersion);
    const std::string version = LANTERN_VERSION_STRING;
    key.insert(key.end(), version.begin(), version.end());
    place.file = folder / ("pipelines-" + hex(fnv1a(key), 16) + ".bin");
    return place;
}

std::vector<std::uint8_t> pipelineCacheFileBytes(std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> out(std::begin(kMagic), std::end(kMagic));
    put(out, kFormat);
    put(out, std::uint32_t(0));
    put(out, std::uint64_t(data.size()));
    put(out, fnv1a(data));
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

std::span<const std::uint8_t> pipelineCacheData(std::span<const std::uint8_t> file,
                                                const VkPhysicalDeviceProperties& props,
                                                std::string& why) {
    if (file.size() < kHeaderBytes) {
        why = "truncated: " + std::to_string(file.size()) + " bytes, shorter than its header";
        return {};
    }
    if (std::memcmp(file.data(), kMagic, sizeof kMagic) != 0) {
        why = "not a Lantern pipeline cache (it does not start with LANTERNP)";
        return {};
    }
    if (const auto format = readAt<std::uint32_t>(file, 8); format != kFormat) {
        why = "written in format " + std::to_string(format) + ", this Lantern reads format 1";
        return {};
    }
    const std::span<const std::uint8_t> data = file.subspan(kHeaderBytes);
    if (const auto size = readAt<std::uint64_t>(file, 16); size != data.size()) {
        why = (size > data.size() ? "truncated: " : "too long: ") + std::to_string(data.size()) +
              " bytes of pipeline data where its header says " + std::to_string(size);
        return {};
    }
    if (readAt<std::uint64_t>(file, 24) != fnv1a(data)) {
        why = "damaged: the checksum of its pipeline data does not match";
        return {};
    }
    // The driver's own header (VkPipelineCacheHeaderVersionOne) must name this device.
    VkPipelineCacheHeaderVersionOne h{};
    if (data.size() < sizeof h) {
        why = "its pipeline data is shorter than Vulkan's header";
        return {};
    }
    std::memcpy(&h, data.data(), sizeof h);
    if (h.headerVersion != VK_PIPELINE_CACHE_HEADER_VERSION_ONE || h.headerSize < sizeof h ||
        h.headerSize > data.size()) {
        why = "its Vulkan header is not VK_PIPELINE_CACHE_HEADER_VERSION_ONE";
        return {};
    }
    if (h.vendorID != props.vendorID || h.deviceID != props.deviceID ||
        std::memcmp(h.pipelineCacheUUID, props.pipelineCacheUUID, VK_UUID_SIZE) != 0) {
        why = "made by another device or driver (vendor 0x" + hex(h.vendorID, 4) + ", device 0x" +
              hex(h.deviceID, 4) + ", cache UUID " + uuidText(h.pipelineCacheUUID) +
              "; this one: vendor 0x" + hex(props.vendorID, 4) + ", device 0x" +
              hex(props.deviceID, 4) + ", cache UUID " + uuidText(props.pipelineCacheUUID) + ")";
        return {};
    }
    return data;
}

Result<PipelineCache> PipelineCache::create(VkDevice device,
                                            const VkPhysicalDeviceProperties& props,
                                            const PipelineCacheSettings& settings,
                                            const LogSink& log) {
    PipelineCache c;
    const PipelineCachePlace place = pipelineCachePlace(settings, props);
    c.m_file = place.file;
    std::span<const std::uint8_t> initial;
    FileRead found;
    if (!c.m_file.empty()) found = readFile(c.m_file);
    if (found.exists) {
        std::string why = found.refused;
        if (why.empty()) initial = pipelineCacheData(found.bytes, props, why);
        if (!why.empty()) warn(log, c.m_file, why + "; ignored, it will be replaced");
        c.m_replace = !why.empty();
    }
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = initial.size();
    info.pInitialData = initial.empty() ? nullptr : initial.data();
    VkPipelineCache cache = VK_NULL_HANDLE;
    VkResult r = vkCreatePipelineCache(device, &info, nullptr, &cache);
    if (r != VK_SUCCESS && !initial.empty()) {
        // A driver may refuse data it does not like: start empty rather than fail.
        warn(log, c.m_file, std::string("the driver refused its data (") + vkResultName(r) +
                                "); ignored, it will be replaced");
        initial = {};
        c.m_replace = true;
        info.initialDataSize = 0;
        info.pInitialData = nullptr;
        r = vkCreatePipelineCache(device, &info, nullptr, &cache);
    }
    if (r != VK_SUCCESS) return vkError(r, "vkCreatePipelineCache");
    c.m_cache = UniquePipelineCache(device, cache);
    c.m_onDisk.assign(initial.begin(), initial.end());
    c.m_loadedBytes = initial.size();
    if (log && !initial.empty())
        log(LogLevel::Info, "pipeline cache: " + std::to_string(initial.size()) +
                                " bytes loaded from " + c.m_file.string());
    return c;
}

bool PipelineCache::save(VkDevice device, const LogSink& log) {
    if (m_file.empty() || !m_cache) return false;
    const std::vector<std::uint8_t> data = driverData(device, m_cache.get());
    if (data.empty() || (data == m_onDisk && !m_replace)) return false;
    std::string error = makeFolder(m_file.parent_path());
    if (error.empty()) error = writeCarefully(m_file, pipelineCacheFileBytes(data));
    if (!error.empty()) {
        warn(log, m_file, "not written (" + error + "); pipelines will be compiled again");
        return false;
    }
    m_onDisk = data;
    m_replace = false;
    if (log)
        log(LogLevel::Debug, "pipeline cache: " + std::to_string(data.size()) +
                                 " bytes written to " + m_file.string());
    return true;
}

} // namespace lantern::gpu
