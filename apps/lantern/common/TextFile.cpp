// A text file written whole or not at all (common/TextFile.h).
#include "common/TextFile.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <random>
#include <sys/random.h>
#include <unistd.h>

namespace lantern::cli {

namespace fs = std::filesystem;

Result<void> writeTextFile(const fs::path& path, const std::string& text) {
    // The temporary is created exclusively under a random name, never through a symlink
    // planted beside the file (a predictable name let one redirect the write).
    std::uint64_t random = 0;
    if (::getrandom(&random, sizeof random, 0) != ssize_t(sizeof random))
        random = std::uint64_t(std::random_device{}()) << 32 ^ std::random_device{}();
    char suffix[40];
    std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%016llx", long(::getpid()),
                  static_cast<unsigned long long>(random));
    const fs::path tmp = path.string() + suffix;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0)
        return makeError(ErrorCode::IoError, "cannot create " + tmp.string() + ": " +
                                                 std::strerror(errno), {}, path.string());
    std::size_t done = 0;
    bool ok = true;
    while (ok && done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        ok = n > 0;
        if (ok) done += std::size_t(n);
    }
    ok = ::close(fd) == 0 && ok;
    if (!ok) {
        ::unlink(tmp.c_str());
        return makeError(ErrorCode::IoError, "cannot write " + tmp.string(), {}, path.string());
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        ::unlink(tmp.c_str());
        return makeError(ErrorCode::IoError, "cannot rename the temporary file into place", {},
                         path.string());
    }
    return {};
}

} // namespace lantern::cli
