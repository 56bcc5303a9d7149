// The list of `lantern bench` subcommands besides `frame`: each benchmark lives in its own file
// and is added here with one line.
#include "Bench.h"

namespace lantern::cli {

std::vector<Runner> addMoreBenchCommands(CLI::App& /*bench*/) {
    return {};
}

} // namespace lantern::cli
