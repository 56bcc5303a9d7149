// Result<T> and Error: how every Lantern call that can fail for a reason outside the caller's
// control (a file, the driver, the OS) reports it. Nothing in Lantern throws across this API,
// aborts or exits the host process.
#pragma once

#include <lantern/Assert.h>
#include <lantern/Export.h>

#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace lantern {

/// What kind of failure an Error is. The command line maps these to exit codes (exitCodeFor).
enum class ErrorCode {
    InvalidInput,  ///< a scene, option or value was refused (bad file, bad number, bad reference)
    Usage,         ///< an API or command-line misuse that the caller can correct
    NoDevice,      ///< no Vulkan device, or none that has what Lantern needs
    DeviceLost,    ///< the device was lost while rendering
    OutOfMemory,   ///< host or device memory ran out, or a request was refused as too large
    IoError,       ///< a file could not be read or written
    Unsupported,   ///< a feature the device or build does not offer
    Cancelled,     ///< the work was stopped on request (for example by SIGINT)
    Internal,      ///< a Vulkan call failed in a way no other code describes
};

/// A stable lower-case name for an ErrorCode ("invalid-input", "no-device", ...).
LANTERN_API const char* errorCodeName(ErrorCode code) noexcept;

/// The `lantern` command's exit status for an error: 1 input refused, 2 usage, 3 renderer failed.
LANTERN_API int exitCodeFor(ErrorCode code) noexcept;

/// A failure: what went wrong, in which file, at which object.
struct LANTERN_API Error {
    ErrorCode code = ErrorCode::Internal;
    std::string message;  ///< what is wrong, one line, no trailing period needed
    std::string file;     ///< the file concerned, if any ("" otherwise)
    std::string object;   ///< the object path, e.g. "materials[3].extensions.X.shininess"

    /// One line: "file: object: message" with the empty parts left out.
    std::string describe() const;
};

/// Builds an Error; `object` and `file` may be empty.
inline Error makeError(ErrorCode code, std::string message, std::string object = {},
                       std::string file = {}) {
    return Error{code, std::move(message), std::move(file), std::move(object)};
}

/// Either a value or an Error (an expected-like type, API-compatible with the parts of
/// std::expected it offers). Accessing the value of a failed Result, or the error of a successful
/// one, is a programming error: LANTERN_ASSERT aborts, in every build type.
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : m_state(std::in_place_index<0>, std::move(value)) {}
    Result(Error error) : m_state(std::in_place_index<1>, std::move(error)) {}

    bool has_value() const noexcept { return m_state.index() == 0; }
    explicit operator bool() const noexcept { return has_value(); }

    T& value() & {
        LANTERN_ASSERT(has_value(), "value() of a failed Result");
        return std::get<0>(m_state);
    }
    const T& value() const& {
        LANTERN_ASSERT(has_value(), "value() of a failed Result");
        return std::get<0>(m_state);
    }
    T&& value() && {
        LANTERN_ASSERT(has_value(), "value() of a failed Result");
        return std::get<0>(std::move(m_state));
    }
    const Error& error() const& {
        LANTERN_ASSERT(!has_value(), "error() of a successful Result");
        return std::get<1>(m_state);
    }
    Error&& error() && {
        LANTERN_ASSERT(!has_value(), "error() of a successful Result");
        return std::get<1>(std::move(m_state));
    }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T&& operator*() && { return std::move(*this).value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

private:
    std::variant<T, Error> m_state;
};

/// Result<void>: success or an Error.
template <>
class [[nodiscard]] Result<void> {
public:
    Result() = default;
    Result(Error error) : m_error(std::move(error)), m_failed(true) {}

    bool has_value() const noexcept { return !m_failed; }
    explicit operator bool() const noexcept { return has_value(); }
    const Error& error() const& {
        LANTERN_ASSERT(m_failed, "error() of a successful Result");
        return m_error;
    }
    Error&& error() && {
        LANTERN_ASSERT(m_failed, "error() of a successful Result");
        return std::move(m_error);
    }

private:
    Error m_error;
    bool m_failed = false;
};

} // namespace lantern

/// Evaluates a Result-returning expression and returns its Error from the enclosing function
/// on failure.
#define LANTERN_TRY(expr)                                                                          \
    do {                                                                                           \
        if (auto lanternTryResult_ = (expr); !lanternTryResult_)                                   \
            return std::move(lanternTryResult_).error();                                           \
    } while (false)
