// AtomicFile.h: output that is complete or absent. A writer fills a temporary file in the
// destination folder; commit() flushes it to disk and renames it over the destination; a
// writer destroyed without commit() removes its temporary file.
#pragma once

#include <lantern/Result.h>

#include <filesystem>
#include <string>

namespace lantern::io {

class AtomicFile {
public:
    /// Chooses a temporary name beside `destination` (".NAME.tmp-PID-N"); nothing is created.
    explicit AtomicFile(std::filesystem::path destination);
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    ~AtomicFile();

    const std::filesystem::path& temporaryPath() const { return m_temporary; }
    const std::filesystem::path& destination() const { return m_destination; }

    /// Checks that the destination folder exists and is writable (IoError otherwise).
    Result<void> checkWritable() const;
    /// Writes `bytes` to the temporary file.
    Result<void> writeAll(const void* data, std::size_t size);
    /// fsyncs the temporary file and renames it to the destination.
    Result<void> commit();

private:
    std::filesystem::path m_destination;
    std::filesystem::path m_temporary;
    bool m_committed = false;
};

/// Removes stale temporary files a killed process left beside `destination` (same name
/// pattern, owned by processes that no longer run). Returns how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& destination);

/// The same for every temporary file in `folder`, whatever its destination name.
std::size_t removeStaleTemporariesIn(const std::filesystem::path& folder);

} // namespace lantern::io
