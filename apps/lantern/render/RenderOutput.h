// RenderOutput.h: what `lantern render` prints and how it runs a sequence (RenderCommand.cpp):
// the --probe report, and the sequence run with its progress, stop signals and summary.
#pragma once

#include <lantern/Lantern.h>
#include <lantern/Sequence.h>

#include <ostream>

namespace lantern::cli {

/// --probe: the lighting equation at one pixel, term by term (Renderer::probe).
void printProbe(std::ostream& out, const ProbeReport& report);

/// Renders the sequence `seq` (progress on stderr, a bar on a terminal; the first SIGINT or
/// SIGTERM stops it cleanly after the frames in hand), prints the paths written on stdout
/// and a summary with the median time per frame on stderr. Returns the exit code: 0, the
/// error's code, or 128 + the signal when stopped.
int runSequence(Renderer& renderer, const PreparedScene& prepared, const RenderOptions& options,
                SequenceOptions seq);

} // namespace lantern::cli
