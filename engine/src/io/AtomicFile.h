// AtomicFile.h: output that is complete or absent. A writer fills a temporary file in the
// destination folder; commit() flushes it to disk and renames it over the destination; a
// writer destroyed without commit() removes its temporary file. Every byte Lantern writes to
// an image goes through write() here, which is where the test-only I/O fault hook sits.
//
// The temporary file is created exclusively (O_CREAT|O_EXCL|O_NOFOLLOW, relative to a
// descriptor of the destination folder) under a name with 64 random bits, so a file or a
// symlink planted beside the output is never opened, followed or overwritten. Its name is
// ".NAME.tmp-lantern-PID-RANDOM" with NAME shortened so that the whole fits the file
// system's name limit; a destination name up to that limit works.
#pragma once

#include <lantern/Result.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace lantern::io {

class AtomicFile {
public:
    /// Chooses a temporary name beside `destination` (".NAME.tmp-lantern-PID-RANDOM"); nothing
    /// is created until open().
    explicit AtomicFile(std::filesystem::path destination);
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    ~AtomicFile();

    const std::filesystem::path& temporaryPath() const { return m_temporary; }
    const std::filesystem::path& destination() const { return m_destination; }

    /// Checks that the destination folder exists and is writable (IoError otherwise).
    Result<void> checkWritable() const;
    /// Creates the temporary file exclusively (a new random name if one exists already);
    /// write() and seek() open it when needed. Called again, it starts the file over.
    Result<void> open();
    /// Writes `size` bytes at the current position. A full disk is an IoError naming the
    /// destination whose message says so ("No space left on device (the disk is full)").
    Result<void> write(const void* data, std::size_t size);
    /// Moves the write position (OpenEXR rewrites its offset table at the end of a file).
    Result<void> seek(std::uint64_t offset);
    /// Writes `bytes` to the temporary file: open(), then write().
    Result<void> writeAll(const void* data, std::size_t size);
    /// fsyncs and closes the temporary file and renames it to the destination.
    Result<void> commit();

private:
    Result<void> openFolder();
    void removeTemporary();

    std::filesystem::path m_destination;
    std::filesystem::path m_temporary;
    std::string m_temporaryName; ///< m_temporary's last component
    int m_dirFd = -1;            ///< the destination folder, for openat/renameat/unlinkat
    int m_fd = -1;
    bool m_created = false;      ///< this object created m_temporaryName (and may remove it)
    bool m_committed = false;
};

/// Removes stale temporary files a killed Lantern process left beside `destination`: only
/// regular files (never a symlink) of this user whose name is exactly Lantern's temporary
/// pattern (".NAME.tmp-lantern-PID-" and 16 hex digits) and whose PID no longer runs. A user's
/// own file whose name merely contains ".tmp-" is never touched. Returns how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& destination);

/// The same for every Lantern temporary file in `folder`, whatever its destination name.
std::size_t removeStaleTemporariesIn(const std::filesystem::path& folder);

/// The temporary name for a destination called `destinationName` with writer `pid` and random
/// part `random` (exposed for tests: it is at most NAME_MAX bytes for any destination name).
std::string temporaryName(const std::string& destinationName, long pid, std::uint64_t random);

/// True when `name` is exactly the pattern temporaryName() makes; its PID in `pid`.
bool isTemporaryName(const std::string& name, long* pid = nullptr);

/// Fault injection for file output (tests only). In builds with LANTERN_TESTING_HOOKS (dev
/// and CI; not release), the environment variable
///     LANTERN_TEST_IO_FAULT="OP=ERRNO[@N][;OP=ERRNO[@N]...]"
/// with OP one of write, fsync, rename and ERRNO one of ENOSPC, EDQUOT, EIO, EROFS lets the
/// first N calls of OP succeed (counted over the whole process, every file; N defaults to 0)
/// and makes every later one fail with ERRNO, as a disk that has filled stays full. The
/// failure then takes the path a real one takes. injectIoFault() arms the same in-process
/// (replacing what was armed for `op`); it returns false, arming nothing, in builds without
/// the hooks.
enum class IoOp { Write, Fsync, Rename };
bool injectIoFault(IoOp op, int error, int after = 0);
void clearIoFaults();

} // namespace lantern::io
