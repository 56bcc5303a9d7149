// The command line's contract: docs/cli.md is what `lantern help --markdown` generates from the
// definition (so the two cannot drift), the README and every --help link only to files in the
// project, the shared options have one name and one description in every subcommand, and a
// mistyped subcommand or option gets the nearest valid name (exit 2); the man pages and the
// bash, zsh and fish completions, generated from the same definition, name every option.
#include "TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace {

using lantern::test::runLantern;
using lantern::test::sourceDir;
using Json = nlohmann::json;

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The definition as `lantern help --json` gives it, one entry per (sub)command.
std::vector<Json> commands() {
    const auto r = runLantern({"help", "--json"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::vector<Json> out;
    std::vector<Json> pending = {Json::parse(r.out, nullptr, false)};
    EXPECT_FALSE(pending.front().is_discarded()) << r.out;
    while (!pending.empty() && !pending.back().is_discarded()) {
        Json c = pending.back();
        pending.pop_back();
        for (const Json& sub : c["subcommands"])
            pending.push_back(sub);
        out.push_back(c);
    }
    return out;
}

TEST(CliReference, DocsMatchTheDefinition) {
    const auto r = runLantern({"help", "--markdown"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string committed = readText(sourceDir() / "docs" / "cli.md");
    if (r.out == committed) return;
    std::istringstream generated(r.out), file(committed);
    std::string a, b;
    int line = 0;
    while (++line, std::getline(generated, a) && std::getline(file, b) && a == b) {
    }
    FAIL() << "docs/cli.md differs from the command's definition at line " << line
           << ":\n  definition: " << a << "\n  docs/cli.md: " << b
           << "\nRegenerate it: " << lantern::test::cliPath().string()
           << " help --markdown > docs/cli.md";
}

TEST(CliReference, EveryOptionIsInTheDocs) {
    const std::string docs = readText(sourceDir() / "docs" / "cli.md");
    for (const Json& c : commands()) {
        EXPECT_NE(docs.find("`" + c["path"].get<std::string>() + "`"), std::string::npos)
            << c["path"];
        for (const Json& o : c["options"])
            for (const Json& name : o["names"])
                EXPECT_NE(docs.find(name.get<std::string>()), std::string::npos)
                    << c["path"] << " " << name;
    }
}

// Markdown links and backquoted project paths of the README must name files of the project.
TEST(CliReference, ReadmeAndHelpLinkOnlyToFilesInTheProject) {
    const std::string readme = readText(sourceDir() / "README.md");
    EXPECT_EQ(readme.find("../shared"), std::string::npos) << "the README points outside";
    static const std::regex link(R"(\]\(([^)#\s]+)[^)]*\))");
    static const std::regex path(R"(`((?:docs|apps|scripts|benchmarks|tests|engine)/[\w./-]+)`)");
    std::set<std::string> targets;
    for (const std::regex* re : {&link, &path})
        for (auto it = std::sregex_iterator(readme.begin(), readme.end(), *re);
             it != std::sregex_iterator(); ++it)
            targets.insert((*it)[1]);
    EXPECT_GT(targets.size(), 5u);
    for (const std::string& t : targets) {
        if (t.rfind("http", 0) == 0) continue;
        EXPECT_TRUE(std::filesystem::exists(sourceDir() / t)) << "README names " << t;
    }
    for (const Json& c : commands()) {
        std::vector<std::string> args;
        std::istringstream words(c["path"].get<std::string>());
        for (std::string w; words >> w;)
            args.push_back(w);
        args.erase(args.begin()); // "lantern"
        args.push_back("--help");
        const auto r = runLantern(args);
        EXPECT_EQ(r.exitCode, 0) << c["path"];
        EXPECT_EQ(r.out.find("shared/spec"), std::string::npos) << c["path"] << ":\n" << r.out;
    }
}

// The options several subcommands share: one set of names each, and one description (one for
// the single value, one for the comma-separated list of a sweep). -o's value differs (a file, a
// pattern, a folder), so only its names are checked.
TEST(CliNames, SharedOptionsHaveOneNameAndOneDescription) {
    const std::map<std::string, std::set<std::string>> canonical = {
        {"--width", {"--width"}},       {"--height", {"--height"}},
        {"--shading", {"--shading"}},   {"--specular", {"--specular"}},
        {"--msaa", {"--msaa"}},         {"--output", {"-o", "--output"}},
        {"--background", {"--background"}}};
    std::map<std::string, std::map<bool, std::set<std::string>>> descriptions;
    std::map<std::string, int> uses;
    for (const Json& c : commands())
        for (const Json& o : c["options"]) {
            std::set<std::string> names;
            for (const Json& n : o["names"])
                names.insert(n.get<std::string>());
            for (const auto& [key, expected] : canonical) {
                if (!names.count(key) && !(key == "--output" && names.count("-o"))) continue;
                ++uses[key];
                EXPECT_EQ(names, expected) << c["path"] << " spells " << key << " differently";
                if (key != "--output")
                    descriptions[key][o["list"].get<bool>()].insert(
                        o["description"].get<std::string>());
            }
        }
    for (const auto& [key, byKind] : descriptions)
        for (const auto& [list, texts] : byKind)
            EXPECT_EQ(texts.size(), 1u) << key << (list ? " (list)" : "") << " is described "
                                        << texts.size() << " ways";
    EXPECT_GE(uses["--width"], 5) << "render, view, bench frame, speed, accuracy, sequence";
    EXPECT_GE(uses["--msaa"], 4);
    EXPECT_GE(uses["--output"], 4);
}

TEST(CliNames, NoSynonymsOfTheSharedNames) {
    const std::set<std::string> synonyms = {"--size", "--sizes", "--resolution", "--resolutions",
                                            "--res", "-w", "--out", "--samples", "--spp",
                                            "--shade", "--shading-mode", "--bg"};
    for (const Json& c : commands())
        for (const Json& o : c["options"])
            for (const Json& n : o["names"]) {
                const std::string name = n.get<std::string>();
                EXPECT_FALSE(synonyms.count(name)) << c["path"] << " has " << name;
                if (name.rfind("--", 0) == 0) {
                    EXPECT_TRUE(std::regex_match(name, std::regex("--[a-z0-9]+(-[a-z0-9]+)*")))
                        << c["path"] << ": " << name << " is not lower-case-with-dashes";
                }
            }
}

TEST(CliSuggest, MistypedNamesGetTheNearestValidName) {
    struct Case {
        std::vector<std::string> args;
        std::string expected;
    };
    const Case cases[] = {
        {{"rendr", "builtin:spheres"}, "did you mean `render`?"},
        {{"veiw"}, "did you mean `view`?"},
        {{"bench", "acuracy"}, "did you mean `accuracy`?"},
        {{"render", "builtin:spheres", "--widht", "64"}, "did you mean --width?"},
        {{"render", "builtin:spheres", "--msa", "4"}, "did you mean --msaa?"},
        {{"view", "builtin:spheres", "--backgrund", "0,0,0"}, "did you mean --background?"},
        {{"info", "--devics"}, "did you mean --devices?"},
        {{"bench", "accuracy", "--resolutions", "64x48"}, "it is now --width"},
        {{"render", "builtin:spheres", "--frobnicate"}, "lantern render --help"},
        {{"zzzzzz"}, "render, view, info, bench, farm, compare, thumbnail, help"},
        // An option's value that is one of the command's options: the option meant was
        // swallowed (CLI11 takes any next word), so `--device --dry-run` would render.
        {{"render", "builtin:spheres", "--device", "--dry-run"},
         "--device: its value is the option --dry-run"},
        {{"render", "builtin:spheres", "-o", "--width", "64"}, "--output: its value is the option --width"},
        {{"bench", "speed", "--device", "-q"}, "--device: its value is the option -q"},
    };
    for (const Case& c : cases) {
        const auto r = runLantern(c.args);
        EXPECT_EQ(r.exitCode, 2) << c.args.front() << ": " << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << "expected \"" << c.expected
                                                             << "\" in: " << r.err;
        EXPECT_EQ(r.out, "") << "nothing rendered";
    }
}

TEST(CliHelp, HelpCommandPrintsTheHelpOfASubcommand) {
    const auto render = runLantern({"help", "render"});
    EXPECT_EQ(render.exitCode, 0) << render.err;
    EXPECT_EQ(render.out, runLantern({"render", "--help"}).out);
    const auto bad = runLantern({"help", "rendr"});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("did you mean `render`?"), std::string::npos) << bad.err;
}

TEST(CliVersion, PrintsWhatABugReportNeeds) {
    const auto r = runLantern({"--version"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const lantern::BuildInfo b = lantern::buildInfo();
    EXPECT_EQ(r.out.rfind("lantern " + b.version + "\n", 0), 0u) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\ncommit: ([0-9a-f]{12}|unknown)\n"))) << r.out;
    for (const std::string& line :
         {"build type: " + b.buildType, "compiler: " + b.compiler, "library: " + b.library,
          "Vulkan loader: " + b.vulkanLoader})
        EXPECT_NE(r.out.find(line + "\n"), std::string::npos) << line << " in:\n" << r.out;
    EXPECT_FALSE(b.buildType.empty() || b.compiler == "unknown");
    EXPECT_TRUE(std::regex_match(b.vulkanLoader, std::regex(R"(\d+\.\d+\.\d+|none)")))
        << b.vulkanLoader;
}


bool haveTool(const std::string& tool) {
    return lantern::test::runProcess({"sh", "-c", "command -v " + tool}).exitCode == 0;
}

std::string manName(std::string path) {
    std::replace(path.begin(), path.end(), ' ', '-');
    return path;
}

// roff writes a hyphen as "\-".
std::string roffName(const std::string& name) {
    std::string out;
    for (char c : name) out += c == '-' ? std::string("\\-") : std::string(1, c);
    return out;
}

// One page per command, each naming every option of its command; groff formats every page
// without a warning.
TEST(CliReference, ManPagesNameEveryOption) {
    const auto dir = lantern::test::testOutputDir();
    const auto r = runLantern({"help", "--man-pages", dir.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const bool groff = haveTool("groff");
    if (!groff) std::cout << "groff is not installed: the pages are checked, not formatted\n";
    for (const Json& c : commands()) {
        const auto page = dir / (manName(c["path"].get<std::string>()) + ".1");
        ASSERT_TRUE(std::filesystem::exists(page)) << page;
        const std::string text = readText(page);
        EXPECT_NE(text.find(".SH SYNOPSIS"), std::string::npos) << page;
        for (const Json& o : c["options"])
            for (const Json& name : o["names"])
                EXPECT_NE(text.find(roffName(name.get<std::string>())), std::string::npos)
                    << page << " " << name;
        if (!groff) continue;
        const auto g = lantern::test::runProcess({"groff", "-man", "-Tutf8", "-ww", "-z", page.string()});
        EXPECT_EQ(g.exitCode, 0) << page;
        EXPECT_EQ(g.err, "") << page;
    }
}

// Each shell's script names every option of every command and parses in its shell.
TEST(CliReference, CompletionsNameEveryOptionAndParse) {
    const auto dir = lantern::test::testOutputDir();
    for (const std::string shell : {"bash", "zsh", "fish"}) {
        const auto r = runLantern({"help", "--completion", shell});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        for (const Json& c : commands())
            for (const Json& o : c["options"]) {
                if (o["positional"].get<bool>()) continue;
                for (const Json& n : o["names"]) {
                    const std::string name = n.get<std::string>();
                    const std::string word = shell != "fish"          ? name
                                             : name.rfind("--", 0) == 0 ? " -l " + name.substr(2)
                                                                        : " -s " + name.substr(1);
                    EXPECT_NE(r.out.find(word), std::string::npos) << shell << " " << c["path"] << " " << name;
                }
            }
        const auto file = dir / ("lantern." + shell);
        std::ofstream(file) << r.out;
        if (!haveTool(shell)) {
            std::cout << shell << " is not installed: its script is not parsed\n";
            continue;
        }
        const auto parsed = lantern::test::runProcess({shell, "-n", file.string()});
        EXPECT_EQ(parsed.exitCode, 0) << shell << ": " << parsed.err;
    }
    const auto bad = runLantern({"help", "--completion", "tcsh"});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("--completion"), std::string::npos) << bad.err;
}

// What bash and fish offer: subcommands, options, option values (after a list's comma) and
// scene files by their extension.
TEST(CliReference, CompletionsOfferSubcommandsOptionsValuesAndScenes) {
    const auto dir = lantern::test::testOutputDir();
    std::filesystem::create_directories(dir / "scenes" / "sub");
    std::ofstream(dir / "scenes" / "a.gltf") << "{}";
    std::ofstream(dir / "scenes" / "b.txt") << "x";
    const auto script = dir / "lantern.bash";
    std::ofstream(script) << runLantern({"help", "--completion", "bash"}).out;
    auto bash = [&](const std::vector<std::string>& words) {
        std::string array;
        for (const std::string& w : words) array += " '" + w + "'";
        const std::string code = "source '" + script.string() + "'; COMP_WORDS=(" + array +
                                 "); COMP_CWORD=" + std::to_string(words.size() - 1) +
                                 "; _lantern; printf '%s\\n' \"${COMPREPLY[@]}\"";
        return lantern::test::runProcess({"bash", "-c", code}).out;
    };
    EXPECT_NE(bash({"lantern", "be"}).find("bench\n"), std::string::npos);
    EXPECT_NE(bash({"lantern", "render", "--sha"}).find("--shading\n"), std::string::npos);
    EXPECT_NE(bash({"lantern", "render", "--shading", "g"}).find("gouraud\n"), std::string::npos);
    EXPECT_NE(bash({"lantern", "render", "--aov", "depth,no"}).find("depth,normal\n"), std::string::npos);
    EXPECT_NE(bash({"lantern", "bench", "accuracy", "--lod-e"}).find("--lod-errors\n"), std::string::npos);
    const std::string files = bash({"lantern", "render", (dir / "scenes").string() + "/"});
    EXPECT_NE(files.find("a.gltf"), std::string::npos) << files;
    EXPECT_NE(files.find("sub"), std::string::npos) << files;
    EXPECT_EQ(files.find("b.txt"), std::string::npos) << files;
    if (!haveTool("fish")) {
        std::cout << "fish is not installed: its completions are not asked\n";
        return;
    }
    const auto fishScript = dir / "lantern.fish";
    std::ofstream(fishScript) << runLantern({"help", "--completion", "fish"}).out;
    auto fish = [&](const std::string& line) {
        return lantern::test::runProcess(
                   {"fish", "--no-config", "-c", "source '" + fishScript.string() + "'; complete -C '" + line + "'"})
            .out;
    };
    EXPECT_NE(fish("lantern ben").find("bench"), std::string::npos);
    EXPECT_NE(fish("lantern render --shading ").find("gouraud"), std::string::npos);
    EXPECT_NE(fish("lantern bench accuracy --lod-").find("--lod-errors"), std::string::npos);
}

} // namespace
