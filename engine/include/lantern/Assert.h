// Assert.h: LANTERN_ASSERT, the check of an invariant that only a programming error can break
// (a caller's misuse of the API, or a bug inside Lantern). Unlike assert() it stays in Release
// builds: on failure it prints the file, the line and the condition to stderr and aborts.
// Failures the environment can cause (files, the driver, memory) are never asserted; they
// return Result errors (Result.h).
#pragma once

#include <lantern/Export.h>

namespace lantern::detail {

/// Prints "lantern: FILE:LINE: assertion failed: CONDITION (MESSAGE)" and aborts.
[[noreturn]] LANTERN_API void assertionFailed(const char* file, int line, const char* condition,
                                              const char* message) noexcept;

} // namespace lantern::detail

/// Aborts with file, line and condition when `condition` is false; `message` says what the
/// caller did wrong (a string literal). Evaluated in every build type.
#define LANTERN_ASSERT(condition, message)                                                         \
    ((condition) ? static_cast<void>(0)                                                            \
                 : ::lantern::detail::assertionFailed(__FILE__, __LINE__, #condition, message))
