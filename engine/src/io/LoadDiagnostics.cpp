// A load's messages and budget (io/LoadDiagnostics.h).
#include "io/LoadDiagnostics.h"

namespace lantern::io {

void Diagnostics::warn(const std::string& object, const std::string& message) const {
    if (!m_log) return;
    std::string line = m_file + ": ";
    if (!object.empty()) line += object + ": ";
    line += message;
    m_log(LogLevel::Warning, line);
}

Result<void> Diagnostics::charge(std::uint64_t count, std::uint64_t each, const std::string& object,
                                 const std::string& what) const {
    Budget& b = *m_budget;
    const std::uint64_t rest = left();
    if (each != 0 && count > rest / each)
        return error(object, what + " would need " +
                                 (count > ~std::uint64_t(0) / each
                                      ? std::string("more than 2^64")
                                      : std::to_string(count * each)) +
                                 " bytes, more than the " + std::to_string(rest) +
                                 " left of the scene's budget (--max-size, " +
                                 std::to_string(b.limit) + " bytes in all)");
    b.used += count * each;
    return {};
}

} // namespace lantern::io
