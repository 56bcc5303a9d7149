// PipelineCache.h: the context's VkPipelineCache, kept on disk between runs so that a second
// process does not compile again what the first one did (docs/performance.md, "Pipeline
// cache"). One file per device, driver and Lantern version, in the user's cache folder:
// $LANTERN_CACHE_DIR, else $XDG_CACHE_HOME/lantern, else ~/.cache/lantern; the environment's
// LANTERN_PIPELINE_CACHE=0 turns it off. The file is Lantern's 32-byte header (magic, format,
// length and checksum of what follows) and then the driver's data, whose own header
// (VkPipelineCacheHeaderVersionOne) must name this device. A file that is damaged, truncated,
// foreign, not a regular file of this user, or a symbolic link is ignored with one warning and
// replaced; a folder that cannot be written is a warning. Nothing about the file ever fails a
// render.
//
// The careful write (a temporary created exclusively beside the file, fsync, rename) is the
// one of io/AtomicFile, written again here because gpu/ may not include io/.
#pragma once

#include "gpu/Handles.h"

#include <lantern/Log.h>
#include <lantern/Result.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace lantern::gpu {

/// Whether and where the cache is kept (RendererDesc::pipelineCacheOnDisk and ...Folder).
struct PipelineCacheSettings {
    bool onDisk = true;
    std::string folder;  ///< empty: the environment's (see above)
};

/// The file a device's pipelines are kept in, or why there is none.
struct PipelineCachePlace {
    std::filesystem::path file;  ///< empty when the cache is off
    std::string off;             ///< why it is off, e.g. "LANTERN_PIPELINE_CACHE=0"
};

/// The folder from the settings and the environment, and the file name for `props`: a hash of
/// its pipelineCacheUUID, vendorID, deviceID, driverVersion and Lantern's version.
PipelineCachePlace pipelineCachePlace(const PipelineCacheSettings& settings,
                                      const VkPhysicalDeviceProperties& props);

/// Lantern's file around the driver's `data` (what save() writes).
std::vector<std::uint8_t> pipelineCacheFileBytes(std::span<const std::uint8_t> data);

/// The driver's data in a file's bytes when the file is whole and was made by `props`'s
/// device and driver; otherwise an empty span and, in `why`, what is wrong with it.
std::span<const std::uint8_t> pipelineCacheData(std::span<const std::uint8_t> file,
                                                const VkPhysicalDeviceProperties& props,
                                                std::string& why);

class PipelineCache {
public:
    PipelineCache() = default;
    /// The cache on `device`, created with the file's data when the file is valid for
    /// `props` (warnings to `log` otherwise). Fails only when Vulkan refuses the cache.
    static Result<PipelineCache> create(VkDevice device, const VkPhysicalDeviceProperties& props,
                                        const PipelineCacheSettings& settings,
                                        const LogSink& log);

    VkPipelineCache get() const { return m_cache.get(); }
    /// The file (empty when the cache is kept in memory only).
    const std::filesystem::path& file() const { return m_file; }
    /// Bytes of the driver's data the cache was created with (0: none).
    std::uint64_t loadedBytes() const { return m_loadedBytes; }

    /// Writes the driver's data to the file when it differs from what the file holds (the
    /// data loaded or last saved); a failure is one warning. True when it wrote.
    bool save(VkDevice device, const LogSink& log);
    void reset() { m_cache.reset(); }

private:
    UniquePipelineCache m_cache;
    std::filesystem::path m_file;
    std::vector<std::uint8_t> m_onDisk;  ///< the driver's data the file holds (when valid)
    bool m_replace = false;              ///< the file exists but was refused: write it anyway
    std::uint64_t m_loadedBytes = 0;
};

} // namespace lantern::gpu
