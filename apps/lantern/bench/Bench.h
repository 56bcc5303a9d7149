// Bench.h: helpers shared by the `lantern bench` subcommands, and the hook through which each
// benchmark file registers its own subcommands under `lantern bench`.
#pragma once

#include "common/Commands.h"

#include <chrono>
#include <vector>

namespace lantern::cli {

double median(std::vector<double> values);
double minimum(const std::vector<double>& values);
double msSince(std::chrono::steady_clock::time_point t0);

/// Registers the bench subcommands other than `frame` (accuracy, speed, sequence, ...).
std::vector<Runner> addMoreBenchCommands(CLI::App& bench);

} // namespace lantern::cli
