// Error codes: stable names, exit codes and one-line descriptions.
#include <lantern/Log.h>
#include <lantern/Result.h>
#include <lantern/Version.h>

namespace lantern {

const char* errorCodeName(ErrorCode code) noexcept {
    switch (code) {
    case ErrorCode::InvalidInput: return "invalid-input";
    case ErrorCode::Usage: return "usage";
    case ErrorCode::NoDevice: return "no-device";
    case ErrorCode::DeviceLost: return "device-lost";
    case ErrorCode::OutOfMemory: return "out-of-memory";
    case ErrorCode::IoError: return "io-error";
    case ErrorCode::Unsupported: return "unsupported";
    case ErrorCode::Cancelled: return "cancelled";
    case ErrorCode::Internal: return "internal";
    }
    return "unknown";
}

int exitCodeFor(ErrorCode code) noexcept {
    switch (code) {
    case ErrorCode::InvalidInput: return 1;
    case ErrorCode::Usage: return 2;
    case ErrorCode::Cancelled: return 130;
    default: return 3;
    }
}

std::string Error::describe() const {
    std::string s;
    if (!file.empty()) s += file + ": ";
    if (!object.empty()) s += object + ": ";
    s += message;
    return s;
}

const char* logLevelName(LogLevel level) noexcept {
    switch (level) {
    case LogLevel::Debug: return "debug";
    case LogLevel::Info: return "info";
    case LogLevel::Warning: return "warning";
    case LogLevel::Error: return "error";
    }
    return "unknown";
}

const char* versionString() noexcept { return LANTERN_VERSION_STRING; }

} // namespace lantern
