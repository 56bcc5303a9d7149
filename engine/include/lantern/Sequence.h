// Sequence.h: rendering an animation to numbered image files: frame ranges, shards for
// spreading a sequence over machines, file-name patterns, and the options and report of
// Renderer::renderSequence (the headless double buffer with parallel encoding).
#pragma once

#include <lantern/Export.h>
#include <lantern/FileOptions.h>
#include <lantern/Result.h>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

/// Frames first..last inclusive.
struct FrameRange {
    int first = 0;
    int last = 0;
    int count() const { return last - first + 1; }
};

/// The most encoder threads a sequence may ask for (SequenceOptions::encoderThreads).
inline constexpr int kMaxEncoderThreads = 256;

/// The most frames one range or list may hold (2^24; longer ones are refused as typos).
inline constexpr int kMaxSequenceFrames = 1 << 24;

/// Parses "A-B" (or a single "A"); frames are >= 0, first <= last, at most kMaxSequenceFrames.
LANTERN_API Result<FrameRange> parseFrameRange(std::string_view text);

/// A shard: frames k with k mod count == index.
struct Shard {
    int index = 0;
    int count = 1;
    bool contains(int frame) const { return frame % count == index; }
};

/// Parses "I/N" with 0 <= I < N.
LANTERN_API Result<Shard> parseShard(std::string_view text);

/// The frames of `range` that `shard` renders, in order (of its first kMaxSequenceFrames).
LANTERN_API std::vector<int> shardFrames(const FrameRange& range, const Shard& shard);

/// Parses a frame list "A,B,C-D" (ranges inclusive, frames >= 0, at least one frame). The
/// frames come back ascending, each once.
LANTERN_API Result<std::vector<int>> parseFrameList(std::string_view text);
/// Writes ascending frames as the shortest "A,B,C-D" text that parseFrameList reads back.
LANTERN_API std::string formatFrameList(const std::vector<int>& frames);
/// The frames of `list` that `shard` renders: those at positions p with p mod count == index.
/// A list is split by position, not frame number, so its shards stay balanced whichever
/// frames it holds.
LANTERN_API std::vector<int> shardFrameList(const std::vector<int>& list, const Shard& shard);

/// Replaces each run of '#' in `pattern` by `frame` zero-padded to the run's length
/// ("out/f_####.exr", 7 -> "out/f_0007.exr"); frames wider than the run are written in full.
LANTERN_API std::string expandFramePattern(std::string_view pattern, int frame);
/// True when `pattern` contains at least one '#'.
LANTERN_API bool hasFramePattern(std::string_view pattern);

/// Progress of a sequence, reported after each frame is written.
struct SequenceProgress {
    int written = 0;          ///< frames written so far
    int total = 0;            ///< frames this run writes
    int lastFrame = -1;       ///< the frame number just written
    double elapsedSeconds = 0.0;
    double framesPerSecond = 0.0;
    double secondsLeft = 0.0;
};

struct SequenceOptions {
    FrameRange frames;
    /// When not empty: render these frames (ascending, from parseFrameList) instead of the
    /// range `frames`; the shard then splits the list by position (shardFrameList).
    std::vector<int> frameList;
    double fps = 24.0;  ///< frame k is rendered at time k / fps seconds
    Shard shard;
    /// Output patterns (.exr or .png, with '#' runs for the frame number); every frame is
    /// written to each.
    std::vector<std::string> outputs;
    ExrOptions exr;
    /// Also write each frame's camera JSON beside each output (writeImageCamera: same name,
    /// .json), before the image. Needs a single view covering the image.
    bool writeCamera = false;
    /// Encoder threads (0: one per core; at most kMaxEncoderThreads). Encoding is the expensive
    /// stage on a CPU renderer.
    int encoderThreads = 0;
    /// Polled between frames: return true to stop (frames already being written finish,
    /// nothing half-written remains). Called on the rendering thread.
    std::function<bool()> shouldStop;
    /// Called on the rendering thread after frames are written.
    std::function<void(const SequenceProgress&)> progress;
};

/// The frames a sequence run renders, in order: its shard of `frameList`, else of `frames`.
LANTERN_API std::vector<int> sequenceFrames(const SequenceOptions& sequence);

/// What a sequence did and how long each stage took.
struct SequenceReport {
    std::vector<int> framesWritten;  ///< in order
    bool stopped = false;            ///< shouldStop() asked to stop
    double wallSeconds = 0.0;
    double cpuSeconds = 0.0;         ///< process CPU time over the sequence (all threads)
    std::vector<double> renderMs;    ///< per frame: plan + record + submit + wait + readback
    std::vector<double> gpuMs;       ///< per frame: GPU render pass (-1 when unavailable)
    std::vector<double> encodeMs;    ///< per frame: encoding and writing all its outputs
    std::uint64_t clampedValues = 0; ///< values clamped to the half range (--half)
    std::size_t peakQueuedFrames = 0;  ///< the most decoded frames waiting at once (memory bound)
};

} // namespace lantern
