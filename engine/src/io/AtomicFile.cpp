// Temporary file + fsync + rename: an output is either complete or absent. The temporary is
// created exclusively under a random name relative to a descriptor of its folder, so nothing
// planted there is followed or overwritten. Also the test-only
// I/O fault hook (LANTERN_TEST_IO_FAULT), on the three calls through which output reaches
// the disk, so that a test can fill the disk without mounting one.
#include "io/AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <cctype>
#include <climits>
#include <cstdio>
#include <random>
#include <sys/random.h>
#include <mutex>
#include <string>
#include <string_view>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::io {
namespace {

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

int renameFile(int dirFd, const char* from, const char* to) {
    if (const int e = injectedIoFault(IoOp::Rename)) {
        errno = e;
        return -1;
    }
    return ::renameat(dirFd, from, dirFd, to);
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

const std::string kTmpMarker = ".tmp-lantern-";
constexpr std::size_t kRandomDigits = 16;

// 64 bits from the kernel's random source (std::random_device when getrandom is unavailable).
std::uint64_t randomBits() {
    std::uint64_t r = 0;
    if (::getrandom(&r, sizeof r, 0) == ssize_t(sizeof r)) return r;
    std::random_device device;
    return (std::uint64_t(device()) << 32) ^ device();
}

// The longest name the folder's file system takes (NAME_MAX when it does not say).
std::size_t nameMax(int dirFd) {
    const long n = dirFd >= 0 ? ::fpathconf(dirFd, _PC_NAME_MAX) : -1;
    return n > 0 ? std::size_t(n) : std::size_t(NAME_MAX);
}

// `name` cut to at most `bytes` bytes, never inside a UTF-8 sequence.
std::string cutName(const std::string& name, std::size_t bytes) {
    if (name.size() <= bytes) return name;
    std::size_t end = bytes;
    while (end > 0 && (static_cast<unsigned char>(name[end]) & 0xC0) == 0x80) --end;
    return name.substr(0, end);
}

std::string temporaryNameWithin(const std::string& destinationName, long pid,
                                std::uint64_t random, std::size_t limit) {
    char hex[kRandomDigits + 1];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(random));
    const std::string suffix = kTmpMarker + std::to_string(pid) + "-" + hex;
    const std::size_t room = limit > suffix.size() + 1 ? limit - suffix.size() - 1 : 0;
    return "." + cutName(destinationName, room) + suffix;
}

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

std::string temporaryName(const std::string& destinationName, long pid, std::uint64_t random) {
    return temporaryNameWithin(destinationName, pid, random, NAME_MAX);
}

bool isTemporaryName(const std::string& name, long* pid) {
    const std::size_t marker = name.rfind(kTmpMarker);
    if (name.size() < 2 || name[0] != '.' || marker == std::string::npos) return false;
    const std::string rest = name.substr(marker + kTmpMarker.size());
    const std::size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || dash > 10) return false;
    for (std::size_t i = 0; i < dash; ++i)
        if (rest[i] < '0' || rest[i] > '9') return false;
    if (rest.size() != dash + 1 + kRandomDigits) return false;
    for (std::size_t i = dash + 1; i < rest.size(); ++i)
        if (!std::isxdigit(static_cast<unsigned char>(rest[i])) ||
            std::isupper(static_cast<unsigned char>(rest[i])))
            return false;
    if (pid) *pid = std::strtol(rest.c_str(), nullptr, 10);
    return true;
}

AtomicFile::AtomicFile(std::filesystem::path destination) : m_destination(std::move(destination)) {
    m_temporaryName = temporaryName(m_destination.filename().string(), long(::getpid()), randomBits());
    m_temporary = m_destination.parent_path() / m_temporaryName;
}

AtomicFile::~AtomicFile() {
    if (m_fd >= 0) ::close(m_fd);
    if (!m_committed) removeTemporary();
    if (m_dirFd >= 0) ::close(m_dirFd);
}

void AtomicFile::removeTemporary() {
    // Only the file this object created: never a name someone else put there.
    if (m_created && m_dirFd >= 0) ::unlinkat(m_dirFd, m_temporaryName.c_str(), 0);
    m_created = false;
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
    const std::string name = m_destination.filename().string();
    if (name.empty() || name == "." || name == "..")
        return makeError(ErrorCode::IoError, "the output names a folder, not a file", {},
                         m_destination.string());
    const long limit = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    if (name.size() > (limit > 0 ? std::size_t(limit) : std::size_t(NAME_MAX)))
        return makeError(ErrorCode::IoError,
                         "the file name is " + std::to_string(name.size()) +
                             " bytes, longer than the file system allows (" +
                             std::to_string(limit > 0 ? limit : long(NAME_MAX)) + ")",
                         {}, m_destination.string());
    return {};
}

Result<void> AtomicFile::openFolder() {
    if (m_dirFd >= 0) return {};
    std::filesystem::path dir = m_destination.parent_path();
    if (dir.empty()) dir = ".";
    m_dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (m_dirFd < 0) return ioError(m_destination, "cannot open the output folder " + dir.string(), errno);
    // The name limit is the folder's file system's (NAME_MAX on Linux's usual ones).
    if (const std::size_t limit = nameMax(m_dirFd); limit != std::size_t(NAME_MAX)) {
        m_temporaryName = temporaryNameWithin(m_destination.filename().string(),
                                              long(::getpid()), randomBits(), limit);
        m_temporary = m_destination.parent_path() / m_temporaryName;
    }
    return {};
}

Result<void> AtomicFile::open() {
    if (m_fd >= 0) {
        // Starting over: the file is this object's own, so truncating it is safe.
        if (::ftruncate(m_fd, 0) != 0 || ::lseek(m_fd, 0, SEEK_SET) < 0)
            return ioError(m_destination, "cannot truncate " + m_temporary.string(), errno);
        return {};
    }
    LANTERN_TRY(openFolder());
    for (int attempt = 0;; ++attempt) {
        m_fd = ::openat(m_dirFd, m_temporaryName.c_str(),
                        O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (m_fd >= 0) break;
        if (errno != EEXIST || attempt >= 16)
            return ioError(m_destination, "cannot create " + m_temporary.string(), errno);
        // Someone else's file (or link) has this name: leave it alone and draw another.
        m_temporaryName = temporaryNameWithin(m_destination.filename().string(), long(::getpid()),
                                              randomBits(), nameMax(m_dirFd));
        m_temporary = m_destination.parent_path() / m_temporaryName;
    }
    m_created = true;
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
    // renameat replaces the destination's directory entry; a symlink there is replaced, never
    // followed.
    const std::string destinationName = m_destination.filename().string();
    if (renameFile(m_dirFd, m_temporaryName.c_str(), destinationName.c_str()) != 0)
        return ioError(m_destination, "cannot rename the finished file into place", errno);
    m_committed = true;
    m_created = false;
    return {};
}

namespace {

// Removes Lantern's temporary files in `folder` whose destination name starts with
// `name` (all when empty) and whose writer process no longer runs: regular files of this user
// only, named exactly as temporaryName() names them, removed relative to the folder's
// descriptor (unlinkat never follows a link).
std::size_t removeStale(const std::filesystem::path& folder, const std::string& name) {
    const std::filesystem::path dir = folder.empty() ? std::filesystem::path(".") : folder;
    const int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd < 0) return 0;
    const std::size_t limit = nameMax(dirFd);
    DIR* listing = ::fdopendir(::dup(dirFd));
    std::size_t removed = 0;
    while (listing) {
        const dirent* entry = ::readdir(listing);
        if (!entry) break;
        const std::string file = entry->d_name;
        long pid = 0;
        if (!isTemporaryName(file, &pid)) continue;
        // The destination's own temporaries: its name, shortened as temporaryName() does.
        const std::size_t marker = file.rfind(kTmpMarker);
        const std::size_t suffix = file.size() - marker;
        if (!name.empty() &&
            file.substr(1, marker - 1) != cutName(name, limit > suffix + 1 ? limit - suffix - 1 : 0))
            continue;
        struct stat st {};
        if (::fstatat(dirFd, file.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) continue;
        if (!S_ISREG(st.st_mode) || st.st_uid != ::geteuid()) continue;
        if (pid <= 0 || ::kill(pid_t(pid), 0) == 0 || errno == EPERM) continue; // still runs
        if (::unlinkat(dirFd, file.c_str(), 0) == 0) ++removed;
    }
    if (listing) ::closedir(listing);
    ::close(dirFd);
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
