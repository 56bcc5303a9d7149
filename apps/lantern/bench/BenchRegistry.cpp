// The list of `lantern bench` subcommands besides `frame`: each benchmark lives in its own file
// and is added here with one line.
#include "bench/Bench.h"

namespace lantern::cli {

Runner addSequenceBench(CLI::App& bench);
Runner addAccuracyBench(CLI::App& bench);
Runner addSpeedBench(CLI::App& bench);

std::vector<Runner> addMoreBenchCommands(CLI::App& bench) {
    return {addSequenceBench(bench), addAccuracyBench(bench), addSpeedBench(bench)};
}

} // namespace lantern::cli
