// The OBJ reader's first pass (ObjInternal.h, scanObj): the text checked line by line the way
// tinyobjloader will split it (lines end with "\n", "\r\n" or a lone "\r"; leading spaces and
// tabs skipped; a keyword and a space or tab), before it is parsed.
#include "io/mesh/ObjInternal.h"

#include <climits>
#include <cstring>

namespace lantern::mesh {
namespace {

bool blank(unsigned char c) { return c == ' ' || c == '\t'; }

// A token of a v/vt/vn line holds only what a decimal number holds. tinyobjloader reads
// anything else ("nan", "inf", words) as 0, which could not be told afterwards.
bool numberLike(std::string_view t) {
    for (const char c : t)
        if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E'))
            return false;
    return !t.empty();
}

// An OBJ index: [-]digits, not 0, magnitude at most 2^31 - 1 (tinyobjloader keeps an int).
bool readIndex(std::string_view t, std::int64_t& out) {
    const bool negative = !t.empty() && t[0] == '-';
    if (negative) t.remove_prefix(1);
    if (t.empty() || t.size() > 10) return false;
    std::int64_t v = 0;
    for (const char c : t) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + (c - '0');
    }
    if (v == 0 || v > INT_MAX) return false;
    out = negative ? -v : v;
    return true;
}

class Scanner {
public:
    Scanner(std::vector<unsigned char>& bytes, const Diagnostics& diag) : m_bytes(bytes), m_diag(diag) {}

    Result<ObjScan> run() {
        const std::size_t size = m_bytes.size();
        char* text = reinterpret_cast<char*>(m_bytes.data());
        std::size_t pos = 0;
        while (pos < size) {
            ++m_line;
            const char* nl = static_cast<const char*>(std::memchr(text + pos, '\n', size - pos));
            std::size_t end = nl ? std::size_t(nl - text) : size;
            std::size_t next = nl ? end + 1 : size;
            if (const void* cr = std::memchr(text + pos, '\r', end - pos)) {
                const std::size_t at = std::size_t(static_cast<const char*>(cr) - text);
                next = at + 1 == end && nl ? end + 1 : at + 1;  // "\r\n", or a lone "\r"
                end = at;
            }
            if (std::memchr(text + pos, '\0', end - pos))
                return refuse("", "a NUL byte: an OBJ file is text");
            LANTERN_TRY(lineOf(text + pos, end - pos));
            pos = next;
        }
        LANTERN_TRY(checkPolylines());
        return std::move(m_scan);
    }

private:
    Error refuse(const std::string& object, const std::string& message) const {
        return m_diag.error(object, message + " (line " + std::to_string(m_line) + ")");
    }

    static std::vector<std::string_view> words(const char* s, std::size_t n, std::size_t from) {
        std::vector<std::string_view> out;
        for (std::size_t i = from; i < n;) {
            while (i < n && blank(static_cast<unsigned char>(s[i]))) ++i;
            const std::size_t start = i;
            while (i < n && !blank(static_cast<unsigned char>(s[i]))) ++i;
            if (i > start) out.emplace_back(s + start, i - start);
        }
        return out;
    }

    Result<void> numbers(const char* s, std::size_t n, std::size_t from, const char* what,
                         std::uint64_t index) {
        for (std::size_t i = from; i < n;) {
            while (i < n && blank(static_cast<unsigned char>(s[i]))) ++i;
            const std::size_t start = i;
            while (i < n && !blank(static_cast<unsigned char>(s[i]))) ++i;
            const std::string_view t(s + start, i - start);
            if (!t.empty() && !numberLike(t))
                return refuse(at(what, index), "\"" + std::string(t.substr(0, 40)) +
                                                   "\" is not a finite number");
        }
        return {};
    }

    Result<void> face(const char* s, std::size_t n) {
        std::uint64_t degree = 0;
        for (std::size_t i = 2; i < n;) {
            while (i < n && blank(static_cast<unsigned char>(s[i]))) ++i;
            const std::size_t start = i;
            while (i < n && !blank(static_cast<unsigned char>(s[i]))) ++i;
            if (i == start) break;
            if (!faceCorner(std::string_view(s + start, i - start)))
                return refuse(at("face", m_scan.degrees.size() + 1),
                              "corner " + std::to_string(degree + 1) + " \"" +
                                  std::string(s + start, std::min<std::size_t>(i - start, 40)) +
                                  "\" is not v, v/vt, v//vn or v/vt/vn with indices from 1 to "
                                  "2^31 - 1 or negative (relative)");
            if (++degree > INT_MAX) return refuse(at("face", m_scan.degrees.size() + 1), "too many corners");
        }
        LANTERN_TRY(reserveCharged(m_scan.degrees, 1, m_diag, "faces"));
        LANTERN_TRY(reserveCharged(m_scan.faceLines, 1, m_diag, "faces"));
        m_scan.degrees.push_back(std::uint32_t(degree));
        m_scan.faceLines.push_back(m_line);
        ++m_scan.faces;
        m_scan.faceCorners += degree;
        return {};
    }

    static bool faceCorner(std::string_view t) {
        std::int64_t x = 0;
        const std::size_t a = t.find('/');
        if (a == std::string_view::npos) return readIndex(t, x);
        if (!readIndex(t.substr(0, a), x)) return false;
        const std::string_view rest = t.substr(a + 1);
        const std::size_t b = rest.find('/');
        if (b == std::string_view::npos) return readIndex(rest, x);           // v/vt
        if (b == 0) return readIndex(rest.substr(1), x);                       // v//vn
        return readIndex(rest.substr(0, b), x) && readIndex(rest.substr(b + 1), x);  // v/vt/vn
    }

    Result<void> polyline(char* s, std::size_t n, bool points);
    Result<void> checkPolylines() const;
    Result<void> lineOf(char* s, std::size_t n);

    std::uint32_t group() {
        if (m_scan.groups.empty() || m_scan.groups.back() != std::pair{m_object, m_material})
            m_scan.groups.emplace_back(m_object, m_material);
        return std::uint32_t(m_scan.groups.size() - 1);
    }

    std::vector<unsigned char>& m_bytes;
    const Diagnostics& m_diag;
    ObjScan m_scan;
    std::size_t m_line = 0;
    std::string m_object, m_material;
};

Result<void> Scanner::polyline(char* s, std::size_t n, bool points) {
    const std::vector<std::string_view> w = words(s, n, 2);
    s[0] = '#';  // read here: tinyobjloader repeats lines and points at each usemtl
    if (w.empty()) return {};  // "l" or "p" alone: nothing to draw
    const char* what = points ? "point element" : "line element";
    ObjPolyline element{m_scan.corners.size(), w.size(), points, group(), m_line};
    LANTERN_TRY(reserveCharged(m_scan.corners, w.size(), m_diag, points ? "points" : "lines"));
    for (std::string_view t : w) {
        // v, or v/vt (a line's texture coordinate); negative indices count back from here.
        const std::size_t slash = t.find('/');
        std::int64_t v = 0, vt = 0;
        const bool ok = readIndex(t.substr(0, slash), v) &&
                        (slash == std::string_view::npos || readIndex(t.substr(slash + 1), vt));
        if (!ok)
            return refuse(at(what, m_scan.polylines.size() + 1),
                          "\"" + std::string(t.substr(0, 40)) + "\" is not v or v/vt with indices from "
                          "1 to 2^31 - 1 or negative (relative)");
        ObjCorner c;
        c.v = v > 0 ? v - 1 : std::int64_t(m_scan.v) + v;
        if (slash != std::string_view::npos) c.vt = vt > 0 ? vt - 1 : std::int64_t(m_scan.vt) + vt;
        if (c.v < 0 || (slash != std::string_view::npos && c.vt < 0))
            return refuse(at(what, m_scan.polylines.size() + 1),
                          "\"" + std::string(t.substr(0, 40)) + "\" reaches before the first vertex");
        m_scan.corners.push_back(c);
    }
    LANTERN_TRY(reserveCharged(m_scan.polylines, 1, m_diag, points ? "points" : "lines"));
    m_scan.polylines.push_back(element);
    return {};
}

Result<void> Scanner::checkPolylines() const {
    for (std::size_t i = 0; i < m_scan.polylines.size(); ++i) {
        const ObjPolyline& p = m_scan.polylines[i];
        for (std::size_t k = p.first; k < p.first + p.count; ++k) {
            const ObjCorner& c = m_scan.corners[k];
            if (std::uint64_t(c.v) >= m_scan.v || (c.vt >= 0 && std::uint64_t(c.vt) >= m_scan.vt))
                return m_diag.error(at(p.points ? "point element" : "line element", i + 1),
                                    "corner " + std::to_string(k - p.first + 1) + " names vertex " +
                                        std::to_string(c.v + 1) + (c.vt >= 0 ? "/" + std::to_string(c.vt + 1) : "") +
                                        "; the file has " + std::to_string(m_scan.v) + " vertices and " +
                                        std::to_string(m_scan.vt) + " texture coordinates (line " +
                                        std::to_string(p.line) + ")");
        }
    }
    return {};
}

Result<void> Scanner::lineOf(char* line, std::size_t length) {
    std::size_t lead = 0;
    while (lead < length && blank(static_cast<unsigned char>(line[lead]))) ++lead;
    char* s = line + lead;
    const std::size_t n = length - lead;
    auto is = [&](const char* word) {
        const std::size_t k = std::strlen(word);
        return n > k && std::memcmp(s, word, k) == 0 && blank(static_cast<unsigned char>(s[k]));
    };
    if (n == 0 || s[0] == '#') return {};
    if (is("v")) return numbers(s, n, 2, "vertex", ++m_scan.v);
    if (is("vn")) return numbers(s, n, 3, "normal", ++m_scan.vn);
    if (is("vt")) return numbers(s, n, 3, "texture coordinate", ++m_scan.vt);
    if (is("l") || is("p")) return polyline(s, n, s[0] == 'p');
    if (is("f")) return face(s, n);
    if (is("vw") || is("t")) {
        s[0] = '#';  // tinyobjloader's skin weights and subdivision tags: nothing Lantern reads
        return {};
    }
    if (n >= 6 && std::memcmp(s, "usemtl", 6) == 0) {  // tinyobjloader's test: no space needed
        const std::vector<std::string_view> w = words(s, n, 6);
        m_material = w.empty() ? std::string() : std::string(w[0]);
        ++m_scan.mtlNames;
        ++m_scan.groupLines;
    } else if (is("g")) {
        const std::vector<std::string_view> w = words(s, n, 2);
        m_object.clear();
        for (std::string_view x : w) m_object += (m_object.empty() ? "" : " ") + std::string(x);
        ++m_scan.groupLines;
    } else if (is("o")) {
        m_object.assign(s + 2, n - 2);
        ++m_scan.groupLines;
    }
    return {};
}

} // namespace

Result<ObjScan> scanObj(std::vector<unsigned char>& bytes, const Diagnostics& diag) {
    return Scanner(bytes, diag).run();
}

Result<void> chargeTinyobj(const ObjScan& scan, const Diagnostics& diag) {
    // tinyobjloader's own arrays (each grown by doubling, so up to twice their size): v (and
    // its colours) 48 bytes a vertex, vt 16, vn 24; a face's record, its corner block and the
    // exported copy about 96 bytes, 36 a corner; a shape (group, object, material) 256.
    const std::uint64_t bytes[][2] = {{scan.v, 48}, {scan.vt, 16}, {scan.vn, 24},
                                      {scan.faces, 96}, {scan.faceCorners, 36},
                                      {scan.groupLines, 256}};
    for (const auto& [count, each] : bytes)
        LANTERN_TRY(diag.charge(count, each, "", "tinyobjloader's model of the file"));
    return {};
}

} // namespace lantern::mesh
