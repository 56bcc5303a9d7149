// The public API's boundaries: every public header compiles on its own (tests/CMakeLists.txt
// generates one translation unit per header that includes only it, with only what an
// installed package provides on the include path, and links them in here), no header pulls
// in Vulkan (except the three that take the host's Vulkan objects), tinygltf, OpenEXR or
// the engine's sources, every declaration a shared libLantern must export is marked
// LANTERN_API, and the `lantern` command includes nothing from engine/src (and its subcommands
// nothing from each other).
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {
std::mutex g_mutex;
std::set<std::string>& compiledAlone() {
    static std::set<std::string> headers;
    return headers;
}
} // namespace

/// Called by each generated translation unit (before main) with the header it compiled.
void lanternPublicHeaderCompiled(const char* header) {
    std::lock_guard lock(g_mutex);
    compiledAlone().insert(header);
}

namespace {

using lantern::test::sourceDir;

const fs::path kIncludeDir = sourceDir() / "engine" / "include";

/// The headers that take the host's own Vulkan objects, and so include vulkan.h.
const std::set<std::string> kVulkanHeaders = {"lantern/ExternalDevice.h", "lantern/Window.h", "lantern/WindowTypes.h",
                                              "lantern/glfw/GlfwWindow.h"};

/// Public headers as `lantern/...` names (Version.h is generated from Version.h.in).
std::vector<std::string> publicHeaders() {
    std::vector<std::string> out;
    for (const auto& entry : fs::recursive_directory_iterator(kIncludeDir / "lantern")) {
        const fs::path p = entry.path();
        if (p.extension() == ".h")
            out.push_back(p.lexically_relative(kIncludeDir).generic_string());
        else if (p.filename() == "Version.h.in")
            out.push_back("lantern/Version.h");
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

fs::path sourceOf(const std::string& header) {
    return header == "lantern/Version.h" ? kIncludeDir / "lantern" / "Version.h.in"
                                         : kIncludeDir / header;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string line; std::getline(s, line);) out.push_back(line);
    return out;
}

/// The targets of a file's #include lines, with the quote or bracket kept ("x.h" or <x.h>).
std::vector<std::string> includesOf(const std::string& text) {
    static const std::regex include(R"(^\s*#\s*include\s*([<"][^>"]+[>"]))");
    std::vector<std::string> out;
    for (const std::string& line : lines(text)) {
        std::smatch m;
        if (std::regex_search(line, m, include)) out.push_back(m[1]);
    }
    return out;
}

TEST(PublicHeaders, EachCompilesOnItsOwn) {
    const auto headers = publicHeaders();
    ASSERT_GE(headers.size(), 10u);
    for (const std::string& h : headers)
        EXPECT_TRUE(compiledAlone().count(h))
            << h << " was not compiled on its own (re-run cmake so that tests/CMakeLists.txt "
                    "generates its translation unit)";
}

// What the public headers may include directly: other public headers, the standard library,
// GLM, and vulkan.h in the three headers that take the host's Vulkan objects. (Transitive
// inclusion is checked by the generated translation units, which fail to compile when
// vulkan.h, tinygltf or OpenEXR arrive through a header that must not bring them.)
TEST(PublicHeaders, IncludeOnlyTheStandardLibraryGlmAndEachOther) {
    const std::regex allowed(R"(^<(lantern/[A-Za-z/]+\.h|glm/[a-z0-9_/]+\.hpp|[a-z_]+)>$)");
    for (const std::string& h : publicHeaders()) {
        SCOPED_TRACE(h);
        for (const std::string& inc : includesOf(readFile(sourceOf(h)))) {
            if (inc == "<vulkan/vulkan.h>") {
                EXPECT_TRUE(kVulkanHeaders.count(h)) << h << " includes vulkan.h";
                continue;
            }
            EXPECT_TRUE(std::regex_match(inc, allowed))
                << h << " includes " << inc
                << " (public headers may include the standard library, GLM and lantern/ only)";
            if (inc.rfind("<lantern/", 0) == 0) {
                const std::string target = inc.substr(1, inc.size() - 2);
                EXPECT_TRUE(fs::exists(sourceOf(target))) << inc << " is not a public header";
                if (!kVulkanHeaders.count(h)) {
                    EXPECT_FALSE(kVulkanHeaders.count(target))
                        << h << " includes " << target << ", which brings vulkan.h";
                }
            }
        }
    }
}

// A shared libLantern is compiled with hidden visibility and exports what LANTERN_API marks:
// every function declared at namespace scope, and every class with members defined in the
// library. (A heuristic reading of the house style: namespace-scope declarations start in
// column 0, members are indented by four spaces.)
TEST(PublicHeaders, MarkWhatTheLibraryExports) {
    static const std::regex skip(
        R"(^(#|//|/\*|\*|\}|\)|namespace|struct|class|enum|using|template|inline|constexpr|static|extern|typedef|friend|LANTERN_API))");
    static const std::regex classStart(R"(^(struct|class)\s+(\[\[\w+\]\]\s+)?(\w+)[^;]*\{\s*$)");
    static const std::regex memberDecl(R"(\)\s*(const)?\s*(noexcept)?\s*(override)?\s*;\s*$)");
    for (const std::string& h : publicHeaders()) {
        SCOPED_TRACE(h);
        const auto ls = lines(readFile(sourceOf(h)));
        std::string previous;
        for (std::size_t i = 0; i < ls.size(); ++i) {
            const std::string& line = ls[i];
            if (line.empty()) continue;
            const bool templated = previous.rfind("template", 0) == 0;
            previous = line;
            if (templated || line.find("LANTERN_API") != std::string::npos) continue;
            std::smatch m;
            if (std::regex_search(line, m, classStart)) {
                // A class: does it declare a member defined elsewhere (in the library)?
                const std::string name = m[3];
                std::string statement;
                for (std::size_t j = i + 1; j < ls.size() && ls[j].rfind("};", 0) != 0; ++j) {
                    const std::string& member = ls[j];
                    if (statement.empty() && (member.size() < 5 || member.rfind("    ", 0) != 0 ||
                                              member[4] == ' ' || member[4] == '/' ||
                                              member[4] == '}'))
                        continue;
                    statement += member.substr(0, member.find("//"));
                    if (member.find(';') == std::string::npos &&
                        member.find('{') == std::string::npos)
                        continue;
                    const auto paren = statement.find('(');
                    const auto assign = statement.find('=');
                    const bool initializer = assign < paren &&
                                             statement.find("operator") == std::string::npos;
                    const bool declared = paren != std::string::npos && !initializer &&
                                          std::regex_search(statement, memberDecl) &&
                                          statement.find("friend") == std::string::npos;
                    EXPECT_FALSE(declared)
                        << name << " declares `" << statement
                        << "`, defined in the library: mark the class LANTERN_API";
                    statement.clear();
                }
            } else if (line[0] != ' ' && !std::regex_search(line, skip) &&
                       line.find('(') != std::string::npos) {
                // A free function declared at namespace scope.
                std::string statement = line;
                for (std::size_t j = i + 1; j < ls.size() &&
                                            statement.find(';') == std::string::npos &&
                                            statement.find('{') == std::string::npos;
                     ++j)
                    statement += ls[j];
                if (statement.find('{') == std::string::npos)
                    ADD_FAILURE() << "`" << line << "` is not marked LANTERN_API";
            }
        }
    }
}

// The `lantern` command and the viewer use the public API only, and so does the Python
// module. A quoted include names one of the app's own headers from its folder
// ("common/CliSupport.h", "PythonScene.h").
TEST(AppsUsePublicApiOnly, NothingFromEngineSrc) {
    const fs::path engineSrc = sourceDir() / "engine" / "src";
    for (const auto& [folder, least] : {std::pair{"lantern", 10u}, std::pair{"python", 2u}}) {
        const fs::path apps = sourceDir() / "apps" / folder;
        std::size_t files = 0;
        for (const auto& entry : fs::recursive_directory_iterator(apps)) {
            const fs::path p = entry.path();
            if (p.extension() != ".cpp" && p.extension() != ".h") continue;
            ++files;
            const fs::path name = p.lexically_relative(apps);
            for (const std::string& inc : includesOf(readFile(p))) {
                const std::string target = inc.substr(1, inc.size() - 2);
                EXPECT_EQ(inc.find("engine/src"), std::string::npos) << name << " includes " << inc;
                if (inc[0] == '"') { // a quoted include must be the app's own header
                    EXPECT_TRUE(fs::exists(apps / target) && !fs::exists(engineSrc / target))
                        << name << " includes " << inc << ", which is not one of apps/" << folder
                        << "'s own headers named from apps/" << folder;
                } else {
                    EXPECT_FALSE(fs::exists(engineSrc / target))
                        << name << " includes " << inc << " from engine/src";
                }
            }
        }
        EXPECT_GE(files, least) << "apps/" << folder << " moved?";
    }
}

// apps/lantern has one folder per subcommand and common/ for what several share. A
// subcommand's files include their own folder's headers and common/'s, never another
// subcommand's; common/ includes only common/. (main.cpp, beside the folders, wires them up.)
TEST(AppsUsePublicApiOnly, SubcommandsIncludeOnlyTheirFolderAndCommon) {
    const fs::path apps = sourceDir() / "apps" / "lantern";
    std::set<std::string> folders;
    for (const auto& entry : fs::recursive_directory_iterator(apps)) {
        const fs::path p = entry.path();
        if (p.extension() != ".cpp" && p.extension() != ".h") continue;
        const fs::path name = p.lexically_relative(apps);
        if (name.parent_path().empty()) continue; // main.cpp
        const std::string folder = name.begin()->string();
        folders.insert(folder);
        for (const std::string& inc : includesOf(readFile(p))) {
            if (inc[0] != '"') continue;
            const std::string from = fs::path(inc.substr(1, inc.size() - 2)).begin()->string();
            if (folder == "common")
                EXPECT_EQ(from, "common")
                    << name << " includes " << inc << ": common/ must not depend on a subcommand";
            else
                EXPECT_TRUE(from == folder || from == "common")
                    << name << " includes " << inc
                    << ": a subcommand includes its own folder and common/ only";
        }
    }
    for (const char* expected : {"common", "render", "view", "bench", "farm", "info"})
        EXPECT_TRUE(folders.count(expected)) << "apps/lantern/" << expected << " moved?";
}

} // namespace
