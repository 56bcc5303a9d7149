// libFuzzer target over the `lantern render` command line: the input is a list of arguments,
// one per line, given to the command after the scene and followed by --dry-run, which checks
// every option and loads the scene but creates no device and writes nothing. Whatever the
// arguments, the command must return 0, 1 (refused) or 2 (usage) with no crash, no escaped
// exception, no sanitizer report and no hang (docs/cli.md's exit statuses; a dry run has no
// renderer to fail with 3). scripts/fuzz.sh gives it a dictionary of every render option,
// read from `lantern help --markdown`, and the seeds in tests/fuzz/cli-seeds/.
#include "common/Commands.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args{"lantern", "render", "builtin:spheres"};
    std::string token;
    for (std::size_t i = 0; i <= size && args.size() < 64; ++i) {
        if (i == size || data[i] == '\n') {
            if (!token.empty()) args.push_back(token);
            token.clear();
        } else if (token.size() < 256) {
            token += char(data[i] == 0 ? ' ' : data[i]);
        }
    }
    // A scene named by the input is a built-in one: the fuzzer reads no file.
    for (std::string& a : args)
        if (a.rfind("builtin:", 0) != 0 && a.find(".gltf") != std::string::npos)
            a = "builtin:" + a;
    args.push_back("--dry-run");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int code = lantern::cli::runCommandLine(int(args.size()), argv.data());
    if (code < 0 || code > 2) {
        std::fprintf(stderr, "lantern render --dry-run returned %d (0, 1 or 2 expected)\n", code);
        std::abort();
    }
    return 0;
}
