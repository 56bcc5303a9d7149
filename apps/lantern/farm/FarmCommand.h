// FarmCommand.h: what `lantern farm submit` (FarmSubmit.cpp) and `lantern farm check`
// (FarmCommand.cpp) share: their options as parsed, and the checks of output patterns and the
// frame lists both report on.
#pragma once

#include "farm/Farm.h"

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace lantern::cli::farm {

struct SubmitArgs {
    std::string scheduler = "slurm";
    std::string frames;
    int tasks = 0;
    std::vector<std::string> outputs;
    std::string partition, time, mem, jobName, lantern, image, k8sNamespace, pvc;
    int cpusPerTask = 0, gpus = 0;
    std::vector<std::string> sbatchArgs, setup;
    bool wait = false, resume = false, noSubmit = false, hold = false;
};

struct CheckArgs {
    std::vector<std::string> outputs;
    std::string frames;
};

/// `lantern farm submit`: `extras` are the arguments farm did not recognise (the scene and the
/// `lantern render` options), `cmd` the submit command (which options were given).
int runSubmit(const SubmitArgs& a, const std::vector<std::string>& extras, const CLI::App& cmd);
/// `lantern farm check`.
int runCheck(const CheckArgs& a);

/// A usage error (exit status 2) naming `object`.
Error usage(const std::string& message, const std::string& object = {});
/// Refuses no outputs, outputs that are not .exr or .png, and outputs without a '#' run.
Result<void> checkOutputs(const std::vector<std::string>& outputs);
/// The output patterns as absolute, normalised paths (what the record stores).
std::vector<std::string> absolutePatterns(const std::vector<std::string>& outputs);
/// Every frame of `r`, ascending.
std::vector<int> rangeFrames(const FrameRange& r);
/// The frames of `missing` (missing or unreadable in any output), each once, ascending.
std::vector<int> missingFrames(const std::vector<MissingFrame>& missing);
/// Prints one line per missing or unreadable file on stdout; returns the frames missing.
int printMissing(const std::vector<MissingFrame>& missing);

} // namespace lantern::cli::farm
