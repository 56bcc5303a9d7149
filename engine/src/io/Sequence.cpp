// Frame ranges, shards and file-name patterns for sequences.
#include <lantern/Sequence.h>

#include <charconv>
#include <cstdio>

namespace lantern {
namespace {

bool parseInt(std::string_view t, int& out) {
    if (t.empty()) return false;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

} // namespace

Result<FrameRange> parseFrameRange(std::string_view text) {
    FrameRange r;
    const auto dash = text.find('-');
    const bool ok = dash == std::string_view::npos
                        ? parseInt(text, r.first) && parseInt(text, r.last)
                        : parseInt(text.substr(0, dash), r.first) && parseInt(text.substr(dash + 1), r.last);
    if (!ok || r.first < 0 || r.last < r.first)
        return makeError(ErrorCode::InvalidInput,
                         "\"" + std::string(text) + "\" is not a frame range A-B with 0 <= A <= B",
                         "--frames");
    return r;
}

Result<Shard> parseShard(std::string_view text) {
    Shard s;
    const auto slash = text.find('/');
    if (slash == std::string_view::npos || !parseInt(text.substr(0, slash), s.index) ||
        !parseInt(text.substr(slash + 1), s.count) || s.count < 1 || s.index < 0 || s.index >= s.count)
        return makeError(ErrorCode::InvalidInput,
                         "\"" + std::string(text) + "\" is not a shard I/N with 0 <= I < N", "--shard");
    return s;
}

std::vector<int> shardFrames(const FrameRange& range, const Shard& shard) {
    std::vector<int> frames;
    for (int k = range.first; k <= range.last; ++k)
        if (shard.contains(k)) frames.push_back(k);
    return frames;
}

bool hasFramePattern(std::string_view pattern) { return pattern.find('#') != std::string_view::npos; }

std::string expandFramePattern(std::string_view pattern, int frame) {
    std::string out;
    for (std::size_t i = 0; i < pattern.size();) {
        if (pattern[i] != '#') {
            out += pattern[i++];
            continue;
        }
        std::size_t run = 0;
        while (i < pattern.size() && pattern[i] == '#') ++run, ++i;
        char buf[32];
        std::snprintf(buf, sizeof buf, "%0*d", int(run), frame);
        out += buf;
    }
    return out;
}

} // namespace lantern
