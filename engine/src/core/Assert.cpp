// LANTERN_ASSERT's failure path: one line on stderr, then abort (the host's crash handling,
// core dumps and debuggers take it from there).
#include <lantern/Assert.h>

#include <cstdio>
#include <cstdlib>

namespace lantern::detail {

void assertionFailed(const char* file, int line, const char* condition,
                     const char* message) noexcept {
    std::fprintf(stderr, "lantern: %s:%d: assertion failed: %s (%s)\n", file, line, condition,
                 message);
    std::fflush(stderr);
    std::abort();
}

} // namespace lantern::detail
