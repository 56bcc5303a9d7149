// `lantern`: the command line (spec/cli.md). Exit status: 0 success, 1 input refused,
// 2 usage error, 3 the renderer failed.
#include "common/CliSupport.h"
#include "common/Commands.h"

#include <iostream>
#include <lantern/Version.h>

int main(int argc, char** argv) {
    using namespace lantern::cli;
    CLI::App app{"Lantern: a Vulkan renderer for the classic camera, light and material model"};
    app.set_version_flag("--version", std::string("lantern ") + lantern::versionString());
    app.require_subcommand(1);
    std::vector<Runner> runners = {addRenderCommand(app), addInfoCommand(app), addBenchCommand(app),
                                   addViewCommand(app)};
    runners.push_back(addFarmCommand(app));
    runners.push_back(addCompareCommand(app));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kUsage;
    }
    for (const Runner& run : runners)
        if (int code = run(); code >= 0) return code;
    return kUsage;
}
