// The `lantern` command as a whole: every subcommand in one CLI11 app, --version with what a bug
// report needs, parsing, the nearest valid name for a mistyped one, and the run.
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "common/Suggest.h"

#include <iostream>
#include <lantern/Version.h>

namespace lantern::cli {
namespace {

// `lantern --version`: the library's build facts and the Vulkan loader found now.
std::string versionText() {
    const BuildInfo b = buildInfo();
    return "lantern " + b.version + "\ncommit: " + b.commit + "\nbuild type: " + b.buildType +
           "\ncompiler: " + b.compiler + "\nlibrary: " + b.library +
           "\nVulkan loader: " + b.vulkanLoader;
}

} // namespace

std::vector<Runner> addAllCommands(CLI::App& app) {
    std::vector<Runner> runners;
    runners.push_back(addRenderCommand(app));
    runners.push_back(addViewCommand(app));
    runners.push_back(addInfoCommand(app));
    runners.push_back(addBenchCommand(app));
    runners.push_back(addFarmCommand(app));
    runners.push_back(addCompareCommand(app));
    runners.push_back(addThumbnailCommand(app));
    runners.push_back(addHelpCommand(app));
    return runners;
}

int runCommandLine(int argc, char** argv) {
    CLI::App app{"Lantern: a Vulkan renderer for the classic camera, light and material model",
                 "lantern"};
    app.set_version_flag("--version", versionText,
                         "Print the version, commit, build type, compiler and Vulkan loader");
    app.require_subcommand(1);
    app.footer("Every subcommand has --help; `lantern help --markdown` prints the reference of "
               "every option (docs/cli.md in Lantern's source).");
    const std::vector<Runner> runners = addAllCommands(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ValidationError& e) {
        // A value outside the range or the choices the help states: a bad option value, refused
        // input (docs/cli.md: exit 1), not a usage error; one line naming the option.
        std::cerr << "lantern: error: " << e.what() << "\n";
        return kRefused;
    } catch (const CLI::ConversionError& e) {
        // Not a number where one is needed, or one too large for its type.
        std::cerr << "lantern: error: " << e.what() << "\n";
        return kRefused;
    } catch (const CLI::ParseError& e) {
        // An unknown name gets the nearest valid one; other errors CLI11 words well itself.
        if (auto diagnosis = diagnoseUnknownName(app, std::vector<std::string>(argv + 1, argv + argc))) {
            std::cerr << "lantern: error: " << *diagnosis << "\n";
            return kUsage;
        }
        app.exit(e);
        return kUsage;
    }
    if (auto swallowed = diagnoseSwallowedOption(app)) {
        std::cerr << "lantern: error: " << *swallowed << "\n";
        return kUsage;
    }
    for (const Runner& run : runners)
        if (int code = run(); code >= 0) return code;
    return kUsage;
}

} // namespace lantern::cli
