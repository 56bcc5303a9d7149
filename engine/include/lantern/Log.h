// Log sinks: Lantern never prints; everything it has to say goes to a sink the host provides.
#pragma once

#include <lantern/Export.h>

#include <functional>
#include <string_view>

namespace lantern {

enum class LogLevel { Debug, Info, Warning, Error };

/// A stable lower-case name for a level ("debug", "info", "warning", "error").
LANTERN_API const char* logLevelName(LogLevel level) noexcept;

/// Receives every message Lantern emits (loader warnings, validation-layer messages, device
/// choice). Called from the thread that made the Lantern call, or, for validation messages,
/// from the driver's thread; a sink must therefore be thread-safe. An empty sink discards.
using LogSink = std::function<void(LogLevel level, std::string_view message)>;

} // namespace lantern
