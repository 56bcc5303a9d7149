// Frame ranges, shards and file-name patterns for sequences.
#include <lantern/Sequence.h>

#include <algorithm>
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

Result<std::vector<int>> parseFrameList(std::string_view text) {
    std::vector<int> frames;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string_view item = text.substr(start, comma - start);
        const std::size_t dash = item.find('-');
        int first = 0, last = 0;
        const bool ok =
            dash == std::string_view::npos
                ? parseInt(item, first) && parseInt(item, last)
                : parseInt(item.substr(0, dash), first) && parseInt(item.substr(dash + 1), last);
        if (!ok || first < 0 || last < first)
            return makeError(ErrorCode::InvalidInput,
                             "\"" + std::string(item) + "\" in \"" + std::string(text) +
                                 "\" is not a frame N or a range A-B with 0 <= A <= B",
                             "--frame-list");
        // One range may not make the list unreasonably long (a typo like 0-2000000000).
        if (frames.size() + std::size_t(last - first) >= std::size_t(1) << 24)
            return makeError(ErrorCode::InvalidInput,
                             "more than 16777216 frames in \"" + std::string(text) + "\"",
                             "--frame-list");
        for (int k = first;; ++k) { // not k <= last: last may be INT_MAX
            frames.push_back(k);
            if (k == last) break;
        }
        start = comma + 1;
    }
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

std::string formatFrameList(const std::vector<int>& frames) {
    std::string out;
    for (std::size_t i = 0; i < frames.size();) {
        std::size_t j = i;
        while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1)
            ++j;
        if (!out.empty()) out += ',';
        out += std::to_string(frames[i]);
        if (j > i) out += '-' + std::to_string(frames[j]);
        i = j + 1;
    }
    return out;
}

std::vector<int> shardFrameList(const std::vector<int>& list, const Shard& shard) {
    std::vector<int> frames;
    for (std::size_t p = std::size_t(shard.index); p < list.size(); p += std::size_t(shard.count))
        frames.push_back(list[p]);
    return frames;
}

std::vector<int> sequenceFrames(const SequenceOptions& sequence) {
    return sequence.frameList.empty() ? shardFrames(sequence.frames, sequence.shard)
                                      : shardFrameList(sequence.frameList, sequence.shard);
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
