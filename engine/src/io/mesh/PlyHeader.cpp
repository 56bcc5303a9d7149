// A PLY header, read and checked before the body is touched (io/mesh/PlyHeader.h).
#include "io/mesh/PlyHeader.h"

#include "io/FileAccess.h"

#include <cstring>
#include <optional>

namespace lantern::mesh {
namespace {

std::optional<PlyType> typeOf(std::string_view name) {
    static const std::pair<const char*, PlyType> kTypes[] = {
        {"char", PlyType::I8},    {"int8", PlyType::I8},     {"uchar", PlyType::U8},
        {"uint8", PlyType::U8},   {"short", PlyType::I16},   {"int16", PlyType::I16},
        {"ushort", PlyType::U16}, {"uint16", PlyType::U16},  {"int", PlyType::I32},
        {"int32", PlyType::I32},  {"uint", PlyType::U32},    {"uint32", PlyType::U32},
        {"float", PlyType::F32},  {"float32", PlyType::F32}, {"double", PlyType::F64},
        {"float64", PlyType::F64}};
    for (const auto& [n, t] : kTypes)
        if (name == n) return t;
    return std::nullopt;
}

/// The header's lines, one at a time (a line ends with "\n", "\r\n" or "\r").
class HeaderLines {
public:
    explicit HeaderLines(const std::vector<unsigned char>& bytes) : m_bytes(bytes) {}
    /// The next line's first words (no header line has more than 5: at most 8 are kept, so a
    /// long comment or a body without end_header costs no memory); false at the end.
    bool next(std::vector<std::string_view>& words) {
        if (m_pos >= m_bytes.size()) return false;
        const char* text = reinterpret_cast<const char*>(m_bytes.data());
        std::size_t end = m_pos;
        while (end < m_bytes.size() && text[end] != '\n' && text[end] != '\r') ++end;
        words.clear();
        for (std::size_t i = m_pos; i < end && words.size() < 8;) {
            while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
            const std::size_t start = i;
            while (i < end && text[i] != ' ' && text[i] != '\t') ++i;
            if (i > start) words.emplace_back(text + start, i - start);
        }
        m_pos = end;
        if (m_pos < m_bytes.size() && text[m_pos] == '\r') ++m_pos;  // "\r\n" or a lone "\r"
        if (m_pos < m_bytes.size() && text[m_pos] == '\n') ++m_pos;
        ++m_line;
        return true;
    }
    std::size_t pos() const { return m_pos; }
    std::size_t line() const { return m_line; }

private:
    const std::vector<unsigned char>& m_bytes;
    std::size_t m_pos = 0, m_line = 0;
};

class HeaderReader {
public:
    HeaderReader(const std::vector<unsigned char>& bytes, const Diagnostics& diag)
        : m_bytes(bytes), m_lines(bytes), m_diag(diag) {}

    Result<PlyHeader> read() {
        std::vector<std::string_view> w;
        if (!m_lines.next(w) || w.size() != 1 || w[0] != "ply")
            return m_diag.error("header", "does not start with a \"ply\" line");
        bool format = false;
        while (m_lines.next(w)) {
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header") {
                if (!format) return refuse("no \"format\" line before end_header");
                m_header.bodyOffset = m_lines.pos();
                m_header.bodyLine = m_lines.line() + 1;
                LANTERN_TRY(checkCounts());
                return std::move(m_header);
            }
            if (w[0] == "format") {
                LANTERN_TRY(formatLine(w));
                format = true;
            } else if (w[0] == "element") {
                LANTERN_TRY(elementLine(w));
            } else if (w[0] == "property") {
                LANTERN_TRY(propertyLine(w));
            } else {
                return refuse("unknown header line \"" + io::printable(w[0], 40) + "\"" +
                              (hasEndHeader() ? "" : "; the file has no end_header line"));
            }
        }
        return m_diag.error("header", "has no end_header line (the file ends in the header)");
    }

private:
    bool hasEndHeader() const {
        const std::string_view text(reinterpret_cast<const char*>(m_bytes.data()), m_bytes.size());
        for (std::size_t at = text.find("end_header"); at != std::string_view::npos;
             at = text.find("end_header", at + 1))
            if (at > 0 && (text[at - 1] == '\n' || text[at - 1] == '\r')) return true;
        return false;
    }

    Error refuse(const std::string& message) const {
        return m_diag.error("header", message + " (line " + std::to_string(m_lines.line()) + ")");
    }

    Result<void> formatLine(const std::vector<std::string_view>& w) {
        if (w.size() != 3) return refuse("a format line is \"format KIND VERSION\"");
        if (w[1] == "ascii") m_header.format = PlyFormat::Ascii;
        else if (w[1] == "binary_little_endian") m_header.format = PlyFormat::BinaryLittleEndian;
        else if (w[1] == "binary_big_endian") m_header.format = PlyFormat::BinaryBigEndian;
        else return refuse("unknown format \"" + io::printable(w[1], 40) + "\"");
        return {};
    }

    Result<void> elementLine(const std::vector<std::string_view>& w) {
        std::int64_t count = 0;
        if (w.size() != 3 || !parseInteger(w[2], count) || count < 0)
            return refuse("an element line is \"element NAME COUNT\" with COUNT an integer >= 0");
        PlyElement e;
        e.name = std::string(w[1].substr(0, 100));
        e.count = std::uint64_t(count);
        m_header.elements.push_back(std::move(e));
        return {};
    }

    Result<void> propertyLine(const std::vector<std::string_view>& w) {
        if (m_header.elements.empty()) return refuse("a property before any element");
        PlyProperty p;
        const bool list = w.size() == 5 && w[1] == "list";
        if (!list && w.size() != 3)
            return refuse("a property line is \"property TYPE NAME\" or \"property list COUNTTYPE TYPE NAME\"");
        const auto type = typeOf(w[list ? 3 : 1]);
        if (!type) return refuse("unknown property type \"" + io::printable(w[list ? 3 : 1], 40) + "\"");
        p.type = *type;
        p.list = list;
        if (list) {
            const auto countType = typeOf(w[2]);
            if (!countType || !plyInteger(*countType))
                return refuse("a list's count type must be an integer type, not \"" +
                              io::printable(w[2], 40) + "\"");
            p.countType = *countType;
        }
        p.name = std::string(w.back().substr(0, 100));
        m_header.elements.back().properties.push_back(std::move(p));
        return {};
    }

    // Every element's records must fit in the body: in binary each takes its scalars' bytes and
    // its lists' counts at least, in ASCII two bytes per value ("0 "). So a header that claims
    // 10^12 vertices is refused before anything is allocated or read.
    Result<void> checkCounts() const {
        const std::uint64_t body = m_bytes.size() - m_header.bodyOffset;
        std::uint64_t need = 0;
        for (const PlyElement& e : m_header.elements) {
            std::uint64_t record = 0;
            for (const PlyProperty& p : e.properties)
                record += m_header.format == PlyFormat::Ascii ? 2 : plySize(p.list ? p.countType : p.type);
            if (record == 0) continue;  // nothing is read for it
            if (e.count > (body + 1) / record || need + e.count * record > body + 1)
                return m_diag.error("header", "element \"" + io::printable(e.name, 40) + "\" claims " +
                                                  std::to_string(e.count) + " records of at least " +
                                                  std::to_string(record) + " bytes, more than the " +
                                                  std::to_string(body) + " bytes after the header");
            need += e.count * record;
        }
        return {};
    }

    const std::vector<unsigned char>& m_bytes;
    HeaderLines m_lines;
    const Diagnostics& m_diag;
    PlyHeader m_header;
};

} // namespace

std::size_t plySize(PlyType type) {
    switch (type) {
    case PlyType::I8: case PlyType::U8: return 1;
    case PlyType::I16: case PlyType::U16: return 2;
    case PlyType::I32: case PlyType::U32: case PlyType::F32: return 4;
    case PlyType::F64: return 8;
    }
    return 0;
}

int PlyElement::find(std::string_view property) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
        if (properties[i].name == property) return int(i);
    return -1;
}

Result<PlyHeader> readPlyHeader(const std::vector<unsigned char>& bytes, const Diagnostics& diag) {
    return HeaderReader(bytes, diag).read();
}

} // namespace lantern::mesh
