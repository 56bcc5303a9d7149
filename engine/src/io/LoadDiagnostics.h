// LoadDiagnostics.h: what every scene format's loader reports through: errors and warnings
// that name the file, and the load's allocation budget (LoadOptions::maxBytes). Shared by
// io/gltf/ and io/mesh/, and by the texture decoder (io/image/TextureDecode.h).
#pragma once

#include <lantern/Log.h>
#include <lantern/Result.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>

namespace lantern::io {

/// Where a load's errors and warnings come from: every message names the file. It also keeps
/// the load's allocation budget: every allocation whose size the file decides (buffers,
/// decoded accessors, decoded images and their decoder's working memory, converted
/// geometry, meshopt- and Draco-decoded data, a mesh file's vertices and faces) is charged
/// with charge() before it is made, and the total may not exceed LoadOptions::maxBytes,
/// however small the file (a count of 10^9 costs 20 bytes of JSON or a PLY header).
class Diagnostics {
public:
    Diagnostics(std::string file, LogSink log, std::uint64_t budget = ~std::uint64_t(0))
        : m_file(std::move(file)), m_log(std::move(log)),
          m_budget(std::make_shared<Budget>(Budget{budget, 0})) {}
    const std::string& file() const { return m_file; }
    /// An InvalidInput error naming the file and `object`.
    Error error(std::string object, std::string message) const {
        return makeError(ErrorCode::InvalidInput, std::move(message), std::move(object), m_file);
    }
    /// An error of another kind (IoError).
    Error error(ErrorCode code, std::string object, std::string message) const {
        return makeError(code, std::move(message), std::move(object), m_file);
    }
    /// A warning: something skipped or repaired. "file: object: message".
    void warn(const std::string& object, const std::string& message) const;
    /// Charges `bytes` (`count` x `each`, overflow-safe) to the load's budget for `object`'s
    /// `what`; an InvalidInput error naming both when the total would exceed it.
    Result<void> charge(std::uint64_t count, std::uint64_t each, const std::string& object,
                        const std::string& what) const;
    /// Returns `bytes` charged earlier for memory freed since (a parsed document, once read).
    void release(std::uint64_t bytes) const {
        m_budget->used -= std::min(bytes, m_budget->used);
    }
    /// Bytes charged so far, the budget, and what is left of it.
    std::uint64_t charged() const { return m_budget->used; }
    std::uint64_t budget() const { return m_budget->limit; }
    std::uint64_t left() const { return m_budget->limit - std::min(m_budget->used, m_budget->limit); }

private:
    struct Budget {
        std::uint64_t limit;
        std::uint64_t used;
    };
    std::string m_file;
    LogSink m_log;
    std::shared_ptr<Budget> m_budget;
};

} // namespace lantern::io
