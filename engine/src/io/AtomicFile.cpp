// Temporary file + fsync + rename: an output is either complete or absent.
#include "io/AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::io {
namespace {

std::atomic<unsigned> g_counter{0};

std::string errnoText(int e) { return std::strerror(e); }

Error ioError(const std::filesystem::path& file, const std::string& what, int e) {
    return makeError(ErrorCode::IoError, what + ": " + errnoText(e), {}, file.string());
}

const std::string kTmpMarker = ".tmp-";

} // namespace

AtomicFile::AtomicFile(std::filesystem::path destination) : m_destination(std::move(destination)) {
    const std::string name = "." + m_destination.filename().string() + kTmpMarker +
                             std::to_string(::getpid()) + "-" + std::to_string(g_counter++);
    m_temporary = m_destination.parent_path() / name;
}

AtomicFile::~AtomicFile() {
    if (!m_committed) ::unlink(m_temporary.c_str());
}

Result<void> AtomicFile::checkWritable() const {
    std::filesystem::path dir = m_destination.parent_path();
    if (dir.empty()) dir = ".";
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0)
        return ioError(m_destination, "the output folder " + dir.string() + " does not exist", errno);
    if (!S_ISDIR(st.st_mode))
        return makeError(ErrorCode::IoError, dir.string() + " is not a folder", {},
                         m_destination.string());
    if (::access(dir.c_str(), W_OK) != 0)
        return ioError(m_destination, "the output folder " + dir.string() + " is not writable", errno);
    return {};
}

Result<void> AtomicFile::writeAll(const void* data, std::size_t size) {
    const int fd = ::open(m_temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return ioError(m_destination, "cannot create " + m_temporary.string(), errno);
    const char* p = static_cast<const char*>(data);
    std::size_t left = size;
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int e = errno;
            ::close(fd);
            return ioError(m_destination, "write failed", e);
        }
        p += n;
        left -= std::size_t(n);
    }
    if (::close(fd) != 0) return ioError(m_destination, "close failed", errno);
    return {};
}

Result<void> AtomicFile::commit() {
    // fsync the data before the rename, so a crash cannot leave a complete-looking empty file.
    const int fd = ::open(m_temporary.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return ioError(m_destination, "cannot reopen " + m_temporary.string(), errno);
    if (::fsync(fd) != 0) {
        const int e = errno;
        ::close(fd);
        return ioError(m_destination, "fsync failed", e);
    }
    ::close(fd);
    if (::rename(m_temporary.c_str(), m_destination.c_str()) != 0)
        return ioError(m_destination, "cannot rename the finished file into place", errno);
    m_committed = true;
    return {};
}

namespace {

// Removes ".NAME.tmp-PID-N" files in `dir` whose NAME starts with `namePrefix` (all when
// empty) and whose writer process no longer runs.
std::size_t removeStale(const std::filesystem::path& folder, const std::string& name) {
    std::size_t removed = 0;
    std::error_code ec;
    const std::filesystem::path dir = folder.empty() ? std::filesystem::path(".") : folder;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        const std::string file = entry.path().filename().string();
        const std::size_t marker = file.rfind(kTmpMarker);
        if (file.empty() || file[0] != '.' || marker == std::string::npos) continue;
        if (!name.empty() && file.substr(1, marker - 1) != name) continue;
        const std::string rest = file.substr(marker + kTmpMarker.size());
        const long pid = std::strtol(rest.c_str(), nullptr, 10);
        if (pid > 0 && ::kill(pid_t(pid), 0) == 0) continue;  // its writer still runs
        if (std::filesystem::remove(entry.path(), ec)) ++removed;
    }
    return removed;
}

} // namespace

std::size_t removeStaleTemporaries(const std::filesystem::path& destination) {
    return removeStale(destination.parent_path(), destination.filename().string());
}

std::size_t removeStaleTemporariesIn(const std::filesystem::path& folder) {
    return removeStale(folder, {});
}

} // namespace lantern::io
