// Frame ranges, shards and file-name patterns for sequences.
#include <lantern/Sequence.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
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
    // A typo like 0-2000000000 would otherwise allocate the frame list until memory runs out.
    if (std::int64_t(r.last) - r.first + 1 > kMaxSequenceFrames)
        return makeError(ErrorCode::InvalidInput,
                         "\"" + std::string(text) + "\" has more than " +
                             std::to_string(kMaxSequenceFrames) + " frames",
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
    if (range.first < 0 || range.last < range.first || shard.count < 1) return frames;
    // At most kMaxSequenceFrames (a longer range is refused by renderSequence); the counter is
    // 64-bit so that a range ending at INT_MAX ends.
    const std::int64_t last =
        std::min<std::int64_t>(range.last, std::int64_t(range.first) + kMaxSequenceFrames - 1);
    for (std::int64_t k = range.first; k <= last; ++k)
        if (shard.contains(int(k))) frames.push_back(int(k));
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
        if (std::int64_t(frames.size()) + (std::int64_t(last) - first) >= kMaxSequenceFrames)
            return makeError(ErrorCode::InvalidInput,
                             "more than " + std::to_string(kMaxSequenceFrames) + " frames in \"" +
                                 std::string(text) + "\"",
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
        // Any run length: the number, then zeros in front up to the run's length (a fixed
        // buffer here once cut long runs, so frames overwrote one another).
        const std::string number = std::to_string(frame < 0 ? -std::int64_t(frame) : frame);
        if (frame < 0) out += '-';
        const std::size_t width = run - (frame < 0 ? 1 : 0);
        if (number.size() < width) out.append(width - number.size(), '0');
        out += number;
    }
    return out;
}

} // namespace lantern
