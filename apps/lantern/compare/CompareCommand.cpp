// `lantern compare REF TEST`: how far TEST is from REF (EXR or PNG), judged against idiff-style
// thresholds. Exit status 0 pass (or warn), 1 fail or refused input, 2 usage. No GPU needed.
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "common/CompareCli.h"

namespace lantern::cli {
namespace {

struct CompareArgs {
    std::string reference, test;
    CompareCliOptions compare;
};

int run(const CompareArgs& a) {
    auto options = a.compare.options();
    if (!options) return report(options.error());
    return a.compare.finish(compareFiles(a.reference, a.test, *options));
}

} // namespace

Runner addCompareCommand(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Compare a test image with a reference (EXR or PNG): errors, PSNR, SSIM, FLIP");
    cmd->add_option("reference", args->reference, "Reference image (.exr or .png)")->required();
    cmd->add_option("test", args->test, "Test image (.exr or .png, like the reference)")->required();
    args->compare.add(*cmd);
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
