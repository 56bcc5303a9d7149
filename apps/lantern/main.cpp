// `lantern`: the command line (docs/cli.md). Exit status: 0 success, 1 input refused,
// 2 usage error, 3 the renderer failed.
#include "common/Commands.h"

int main(int argc, char** argv) {
    return lantern::cli::runCommandLine(argc, argv);
}
