// CompareCli.h: the comparison options and report shared by `lantern compare` and
// `lantern render --compare` (thresholds in the manner of OpenImageIO's idiff).
#pragma once

#include <CLI/CLI.hpp>
#include <lantern/Lantern.h>
#include <optional>
#include <string>

namespace lantern::cli {

struct CompareCliOptions {
    std::string metric = "abs";
    double fail = 1e-6, failPercent = 0.0, warnPercent = 0.0;
    std::optional<double> warn;
    double tolerance = -1.0;
    std::string flip = "auto";
    double ppd = CompareOptions{}.pixelsPerDegree;
    bool noSsim = false;
    std::string diff, json;
    bool quiet = false;

    void add(CLI::App& app);
    /// The options for compareImages; a bad --metric, --flip, --diff or --json is a usage error.
    Result<CompareOptions> options() const;
    /// Prints the report (unless --quiet), writes --diff and --json; exit status: 0 pass or
    /// warn, 1 fail, or the error's.
    int finish(const Result<CompareReport>& report) const;
};

/// `render --compare REF`: compares a rendered picture with REF, encoded as REF is (an EXR's
/// linear floats with the AOV planes, or a PNG's 8-bit sRGB values).
int compareRendered(const CompareCliOptions& options, const std::string& reference,
                    const Image& image, const std::string& renderName);

} // namespace lantern::cli
