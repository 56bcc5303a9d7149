// Temporary file + fsync + rename: an output is either complete or absent. Also the test-only
// I/O fault hook (LANTERN_TEST_IO_FAULT), on the three calls through which output reaches
// the disk, so that a test can fill the disk without mounting one.
#include "io/AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <string>
#include <string_view>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::io {
namespace {

std::atomic<unsigned> g_counter{0};

#ifdef LANTERN_TESTING_HOOKS
struct IoFault {
    int error = 0;   // errno to report; 0: none armed
    long after = 0;  // calls still to let through
};
std::mutex g_faultMutex;
IoFault g_faults[3];  // by IoOp
std::atomic<bool> g_faultArmed{false};
std::once_flag g_faultEnvironment;

void armIoFault(IoOp op, int error, long after) {
    std::lock_guard lock(g_faultMutex);
    g_faults[int(op)] = {error, after};
    g_faultArmed = true;
}

// LANTERN_TEST_IO_FAULT="OP=ERRNO[@N][;...]", read once, at the first output call.
void armIoFaultsFromEnvironment() {
    const char* env = std::getenv("LANTERN_TEST_IO_FAULT");
    if (!env) return;
    const std::string_view spec(env);
    std::size_t start = 0;
    while (start < spec.size()) {
        std::size_t end = spec.find(';', start);
        if (end == std::string_view::npos) end = spec.size();
        const std::string_view item = spec.substr(start, end - start);
        start = end + 1;
        const std::size_t eq = item.find('=');
        if (eq == std::string_view::npos) continue;
        const std::string_view name = item.substr(0, eq);
        std::string_view error = item.substr(eq + 1);
        long after = 0;
        if (const std::size_t at = error.find('@'); at != std::string_view::npos) {
            after = std::strtol(std::string(error.substr(at + 1)).c_str(), nullptr, 10);
            error = error.substr(0, at);
        }
        const std::pair<std::string_view, IoOp> ops[] = {
            {"write", IoOp::Write}, {"fsync", IoOp::Fsync}, {"rename", IoOp::Rename}};
        const std::pair<std::string_view, int> errors[] = {
            {"ENOSPC", ENOSPC}, {"EDQUOT", EDQUOT}, {"EIO", EIO}, {"EROFS", EROFS}};
        for (const auto& [opName, op] : ops)
            for (const auto& [errorName, e] : errors)
                if (name == opName && error == errorName) armIoFault(op, e, after);
    }
}

// The errno an armed fault makes this call of `op` fail with, or 0.
int injectedIoFault(IoOp op) {
    std::call_once(g_faultEnvironment, armIoFaultsFromEnvironment);
    if (!g_faultArmed.load(std::memory_order_relaxed)) return 0;
    std::lock_guard lock(g_faultMutex);
    IoFault& f = g_faults[int(op)];
    if (f.error == 0) return 0;
    if (f.after > 0) {
        --f.after;
        return 0;
    }
    return f.error;  // and stays armed: a full disk stays full
}
#else
constexpr int injectedIoFault(IoOp) { return 0; }
#endif

// The three calls through which output reaches the disk, each failing as the hook says.
ssize_t writeSome(int fd, const void* data, std::size_t size) {
    if (const int e = injectedIoFault(IoOp::Write)) {
        errno = e;
        return -1;
    }
    return ::write(fd, data, size);
}

int syncFile(int fd) {
    if (const int e = injectedIoFault(IoOp::Fsync)) {
        errno = e;
        return -1;
    }
    return ::fsync(fd);
}

int renameFile(const char* from, const char* to) {
    if (const int e = injectedIoFault(IoOp::Rename)) {
        errno = e;
        return -1;
    }
    return ::rename(from, to);
}

std::string errnoText(int e) {
    std::string text = std::strerror(e);
    // strerror's words alone do not tell a user what to do about the two common causes.
    if (e == ENOSPC) text += " (the disk is full)";
    if (e == EDQUOT) text += " (the disk quota is used up)";
    return text;
}

Error ioError(const std::filesystem::path& file, const std::string& what, int e) {
    return makeError(ErrorCode::IoError, what + ": " + errnoText(e), {}, file.string());
}

const std::string kTmpMarker = ".tmp-";

} // namespace

bool injectIoFault(IoOp op, int error, int after) {
#ifdef LANTERN_TESTING_HOOKS
    std::call_once(g_faultEnvironment, armIoFaultsFromEnvironment);
    armIoFault(op, error, after);
    return true;
#else
    (void)op, (void)error, (void)after;
    return false;
#endif
}

void clearIoFaults() {
#ifdef LANTERN_TESTING_HOOKS
    std::call_once(g_faultEnvironment, armIoFaultsFromEnvironment);
    std::lock_guard lock(g_faultMutex);
    for (IoFault& f : g_faults) f = {};
    g_faultArmed = false;
#endif
}

AtomicFile::AtomicFile(std::filesystem::path destination) : m_destination(std::move(destination)) {
    const std::string name = "." + m_destination.filename().string() + kTmpMarker +
                             std::to_string(::getpid()) + "-" + std::to_string(g_counter++);
    m_temporary = m_destination.parent_path() / name;
}

AtomicFile::~AtomicFile() {
    if (m_fd >= 0) ::close(m_fd);
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

Result<void> AtomicFile::open() {
    if (m_fd >= 0) ::close(m_fd);
    m_fd = ::open(m_temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (m_fd < 0) return ioError(m_destination, "cannot create " + m_temporary.string(), errno);
    return {};
}

Result<void> AtomicFile::write(const void* data, std::size_t size) {
    if (m_fd < 0) LANTERN_TRY(open());
    const char* p = static_cast<const char*>(data);
    std::size_t left = size;
    while (left > 0) {
        const ssize_t n = writeSome(m_fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return ioError(m_destination, "write failed", errno);
        }
        p += n;
        left -= std::size_t(n);
    }
    return {};
}

Result<void> AtomicFile::seek(std::uint64_t offset) {
    if (m_fd < 0) LANTERN_TRY(open());
    if (::lseek(m_fd, off_t(offset), SEEK_SET) < 0)
        return ioError(m_destination, "seek failed", errno);
    return {};
}

Result<void> AtomicFile::writeAll(const void* data, std::size_t size) {
    LANTERN_TRY(open());
    return write(data, size);
}

Result<void> AtomicFile::commit() {
    if (m_fd < 0) LANTERN_TRY(open());
    // fsync the data before the rename, so a crash cannot leave a complete-looking empty file.
    if (syncFile(m_fd) != 0) return ioError(m_destination, "fsync failed", errno);
    // close() can report a deferred write error (NFS reports a full disk there).
    const int fd = m_fd;
    m_fd = -1;
    if (::close(fd) != 0) return ioError(m_destination, "close failed", errno);
    if (renameFile(m_temporary.c_str(), m_destination.c_str()) != 0)
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
