// Export.h: LANTERN_API marks the public API, which is all a shared libLantern exports; the
// library is compiled with hidden visibility, so the engine's internals stay internal.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define LANTERN_API __attribute__((visibility("default")))
#else
#define LANTERN_API
#endif
