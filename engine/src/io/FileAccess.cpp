// Files read for a scene, by every format: the scene file itself (a regular file, never a
// FIFO or device, within the size bound) and the files it names (URIs, MTL libraries, texture
// paths), resolved to their real paths and refused unless they lie inside the scene's folder
// (or a folder the user allowed), then opened one component at a time so that nothing swapped
// in meanwhile is followed (io/FileAccess.h).
#include "io/FileAccess.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::io {
namespace {

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

} // namespace

std::string percentDecode(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size()) {
            const int hi = hexValue(text[i + 1]), lo = hexValue(text[i + 2]);
            if (hi >= 0 && lo >= 0) {
                out += char(hi * 16 + lo);
                i += 2;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

std::string printable(std::string_view text, std::size_t limit) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (out.size() >= limit) return out + "...";
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 32 && c < 127) {
            out += char(c);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", unsigned(c));
            out += buf;
        }
    }
    return out;
}

namespace {

const char* fileKind(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISLNK(mode)) return "a symbolic link";
    return "not a regular file";
}

std::string sizeProblem(std::uint64_t size, std::uint64_t maxBytes) {
    return "is " + std::to_string(size) + " bytes, more than --max-size (" +
           std::to_string(maxBytes) + " bytes)";
}

} // namespace

namespace {

// Reads the regular file open on `fd` (closed here): checked with fstat before a byte is read.
Result<std::vector<unsigned char>> readOpenedFile(int fd, std::uint64_t maxBytes) {
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        const std::string kind = fileKind(st.st_mode);
        ::close(fd);
        return makeError(ErrorCode::InvalidInput, "is " + kind + ", not a regular file");
    }
    if (std::uint64_t(st.st_size) > maxBytes) {
        ::close(fd);
        return makeError(ErrorCode::InvalidInput, sizeProblem(std::uint64_t(st.st_size), maxBytes));
    }
    std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int e = n < 0 ? errno : 0;
            ::close(fd);
            return makeError(ErrorCode::IoError,
                             e ? std::string("cannot be read: ") + std::strerror(e)
                               : std::string("became shorter while it was read"));
        }
        done += std::size_t(n);
    }
    ::close(fd);
    return bytes;
}

} // namespace

Result<std::vector<unsigned char>> readRegularFile(const std::filesystem::path& path,
                                                   std::uint64_t maxBytes, bool noFollow) {
    const int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC | (noFollow ? O_NOFOLLOW : 0);
    const int fd = ::open(path.c_str(), flags);
    if (fd < 0) {
        const int e = errno;
        if (e == ENOENT) return makeError(ErrorCode::InvalidInput, "does not exist");
        if (e == ELOOP && noFollow) return makeError(ErrorCode::InvalidInput, "is a symbolic link");
        return makeError(ErrorCode::IoError, std::string("cannot be opened: ") + std::strerror(e));
    }
    return readOpenedFile(fd, maxBytes);
}

Result<std::string> readFileStart(const std::filesystem::path& path, std::size_t count) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const int e = errno;
        if (e == ENOENT) return makeError(ErrorCode::InvalidInput, "does not exist");
        return makeError(ErrorCode::IoError, std::string("cannot be opened: ") + std::strerror(e));
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        const std::string kind = fileKind(st.st_mode);
        ::close(fd);
        return makeError(ErrorCode::InvalidInput, "is " + kind + ", not a regular file");
    }
    std::string bytes(count, '\0');
    std::size_t done = 0;
    while (done < count) {
        const ssize_t n = ::read(fd, bytes.data() + done, count - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        done += std::size_t(n);
    }
    ::close(fd);
    bytes.resize(done);
    return bytes;
}

std::filesystem::path ConfinedPath::real() const { return root / relative; }

Result<std::vector<unsigned char>> readConfinedFile(const ConfinedPath& file,
                                                    std::uint64_t maxBytes) {
    const auto changed = [](const char* what) {
        return makeError(ErrorCode::InvalidInput,
                         std::string("changed while it was opened (") + what +
                             "); it is not read");
    };
    int dir = ::open(file.root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
    if (dir < 0)
        return makeError(ErrorCode::IoError,
                         std::string("its folder cannot be opened: ") + std::strerror(errno));
    // One component at a time, each opened relative to the folder opened before it and never
    // through a symbolic link: the path resolveConfined checked is the path read, whatever
    // was renamed or linked since (as openat2's RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS).
    std::vector<std::string> parts;
    for (const std::filesystem::path& part : file.relative) parts.push_back(part.string());
    if (parts.empty()) {
        ::close(dir);
        return changed("an empty path");
    }
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const bool last = i + 1 == parts.size();
        if (parts[i] == ".." || parts[i] == "." || parts[i].empty()) {
            ::close(dir);
            return changed("a relative component");
        }
        const int flags = O_RDONLY | O_CLOEXEC | O_NOFOLLOW | (last ? O_NONBLOCK : O_DIRECTORY);
        const int next = ::openat(dir, parts[i].c_str(), flags);
        const int e = errno;
        ::close(dir);
        if (next < 0) {
            if (e == ELOOP || e == ENOTDIR) return changed("a symbolic link appeared in its path");
            if (e == ENOENT) return changed("it no longer exists");
            return makeError(ErrorCode::IoError, std::string("cannot be opened: ") + std::strerror(e));
        }
        dir = next;
    }
    return readOpenedFile(dir, maxBytes);
}

Result<ConfinedPath> resolveConfined(const std::filesystem::path& folder,
                                              const std::string& relative,
                                              std::uint64_t maxBytes,
                                              const std::vector<std::filesystem::path>& allowed) {
    const std::string shown = "\"" + printable(relative) + "\"";
    auto realOf = [](const std::filesystem::path& p) -> std::optional<std::filesystem::path> {
        char buf[PATH_MAX];
        if (!::realpath(p.c_str(), buf)) return std::nullopt;
        return std::filesystem::path(buf);
    };
    const auto realFolder = realOf(folder);
    if (!realFolder)
        return makeError(ErrorCode::IoError, "the scene's folder cannot be resolved: " +
                                                 std::string(std::strerror(errno)));
    const std::filesystem::path named = folder / relative;
    struct stat st {};
    if (::lstat(named.c_str(), &st) != 0)
        return makeError(ErrorCode::InvalidInput, shown + " does not exist in the scene's folder");
    const auto real = realOf(named);
    if (!real)
        return makeError(ErrorCode::InvalidInput,
                         shown + " cannot be resolved (a broken or looping symbolic link?)");
    auto within = [&](const std::filesystem::path& realRoot) {
        const std::string inside = realRoot.string() == "/" ? "/" : realRoot.string() + "/";
        return real->string().compare(0, inside.size(), inside) == 0;
    };
    std::optional<std::filesystem::path> root;
    if (within(*realFolder)) root = *realFolder;
    for (const std::filesystem::path& a : allowed)
        if (const auto realAllowed = realOf(a); !root && realAllowed && within(*realAllowed))
            root = *realAllowed;
    if (!root)
        return makeError(ErrorCode::InvalidInput,
                         shown + (allowed.empty()
                                      ? " is a symbolic link that leads outside the scene's folder"
                                      : " leads outside the scene's folder and the allowed "
                                        "folders (--allow-folder)"));
    if (::stat(real->c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        return makeError(ErrorCode::InvalidInput,
                         shown + " is " + fileKind(st.st_mode) + ", not a regular file");
    if (std::uint64_t(st.st_size) > maxBytes)
        return makeError(ErrorCode::InvalidInput,
                         shown + " " + sizeProblem(std::uint64_t(st.st_size), maxBytes));
    return ConfinedPath{*root, real->lexically_relative(*root)};
}

Result<std::string> checkRelativeUri(std::string_view uri, const std::string& object,
                                     const std::string& file, bool allowParent) {
    const auto refuse = [&](std::string message) {
        return makeError(ErrorCode::InvalidInput, std::move(message), object, file);
    };
    const std::string path = percentDecode(uri);
    const std::string shown = "\"" + printable(uri) + "\"";
    if (path.empty()) return refuse("URI is empty");
    if (path.find('\0') != std::string::npos)
        return refuse("URI " + shown + " contains a NUL character");
    // A scheme ("http:", "file:") is a colon before the first slash. Only relative paths and
    // data: URIs are read: a scene file must not make the loader fetch or open anything else.
    const std::size_t colon = path.find(':'), slash = path.find('/');
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
        return refuse("URI " + shown +
                                      " has a scheme; only relative paths and data: URIs are read");
    if (path[0] == '/' || path[0] == '\\')
        return refuse("URI " + shown +
                                      " is an absolute path; external files must lie in the "
                                      "scene's folder");
    // ".." anywhere as a path component (either separator) could leave the folder.
    std::size_t start = 0;
    while (!allowParent && start <= path.size()) {
        std::size_t end = path.find_first_of("/\\", start);
        if (end == std::string::npos) end = path.size();
        if (path.compare(start, end - start, "..") == 0)
            return refuse("URI " + shown +
                                          " contains \"..\"; external files must lie in the "
                                          "scene's folder (or one given with --allow-folder)");
        start = end + 1;
    }
    return path;
}

} // namespace lantern::io
