// The house's boundaries, checked on the source tree (docs/ARCHITECTURE.md lists them):
//   - only engine/src/gpu calls Vulkan or includes its headers (and engine/src/glfw for the
//     surface, and apps/examples, which are hosts);
//   - each room of engine/src includes only the rooms below it, so dependencies run one way
//     and no include cycle exists between rooms; render/ and api/ see gpu/ only through its
//     Vulkan-free interface headers;
//   - each public header <lantern/X.h> belongs to the room that implements it (the types'
//     headers to the lowest room that may hold them, the entry points to api/): a room includes
//     only the public headers of itself and the rooms below it, and a public header only those
//     of its room and below, so <lantern/Io.h> and <lantern/Renderer.h> are api/'s alone;
//   - apps/ and benchmarks/ are hosts: any public header, Vulkan only in apps/examples.
// The rules are also tested on made-up files, so a rule that could never fire would show.
// (tests/CMakeLists.txt adds the compile-time half: every internal header outside gpu/ and
// gpu's interface headers compile alone without bringing vulkan.h.)
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace {

using lantern::test::sourceDir;

// What each room of engine/src may include, besides itself. Dependencies run one way:
// api -> {render, io} -> ... ; render -> {gpu (interface), reference} -> frame -> scene ->
// math -> core.
const std::map<std::string, std::set<std::string>> kRoomIncludes = {
    {"core", {}},
    {"math", {"core"}},
    {"scene", {"core", "math"}},
    {"io", {"core", "math", "scene", "compare"}},
    {"frame", {"core", "math", "scene"}},
    {"reference", {"core", "math", "scene", "frame"}},
    {"gpu", {"core", "math", "scene", "frame"}},
    {"render", {"core", "math", "scene", "frame", "reference", "gpu"}},
    {"api", {"core", "math", "scene", "frame", "reference", "render", "io", "gpu", "compare"}},
    {"glfw", {"core", "math", "scene", "io", "frame", "reference", "gpu", "render", "api",
              "compare"}},  // a host library: the public API only (no engine/src, checked below)
    {"compare", {"core"}},  // image comparison: device-free, no Vulkan
};

// The room of each public header: the one that implements what it declares, or for a header of
// types only the lowest room its own includes allow. The entry points (Io.h, Renderer.h,
// Window.h, Lantern.h) are api/'s; glfw/GlfwWindow.h is the GLFW host library's.
const std::map<std::string, std::string> kPublicHeaderRooms = {
    {"Assert.h", "core"},      {"Result.h", "core"},       {"Log.h", "core"},
    {"Export.h", "core"},      {"Version.h", "core"},      {"Image.h", "core"},
    {"Cryptomatte.h", "core"}, {"RenderTypes.h", "core"},  {"Camera.h", "math"},
    {"CameraConventions.h", "math"}, {"Scene.h", "scene"}, {"Probe.h", "scene"},
    {"FileOptions.h", "io"},   {"Sequence.h", "io"},       {"Options.h", "frame"},
    {"Reference.h", "reference"}, {"Compare.h", "compare"}, {"ExternalDevice.h", "gpu"},
    {"WindowTypes.h", "gpu"},  {"Io.h", "api"},            {"Renderer.h", "api"},
    {"Window.h", "api"},       {"Lantern.h", "api"},       {"glfw/GlfwWindow.h", "glfw"},
};

// Whether room `room` may include what room `target` holds.
bool mayInclude(const std::string& room, const std::string& target) {
    if (room == target) return true;
    const auto allowed = kRoomIncludes.find(room);
    return allowed != kRoomIncludes.end() && allowed->second.count(target);
}

// gpu/ as the rooms above it see it: no Vulkan type in these headers.
const std::set<std::string> kGpuInterface = {"gpu/Device.h", "gpu/DrawList.h", "gpu/GpuLayouts.h"};
// The window API hands the host's Vulkan handles to the presenter (lantern/Window.h is the
// public API that carries them).
const std::set<std::string> kWindowException = {"engine/src/api/WindowTarget.cpp"};

// Shader-side headers: the shared constants, and the generated SPIR-V registry.
const std::map<std::string, std::set<std::string>> kNonRoomIncludes = {
    {"lantern_shared.h", {"gpu", "reference", "render"}},
    {"ShaderBlobs.h", {"gpu"}},
};

struct SourceFile {
    std::string path;  ///< relative to the checkout, '/'-separated
    std::string text;
};

// The room of a public header file (engine/include/lantern/X.h), or empty.
std::string publicRoomOf(const std::string& path) {
    const std::string prefix = "engine/include/lantern/";
    if (path.rfind(prefix, 0) != 0) return {};
    std::string name = path.substr(prefix.size());
    if (name == "Version.h.in") name = "Version.h";
    const auto it = kPublicHeaderRooms.find(name);
    return it == kPublicHeaderRooms.end() ? std::string("?") : it->second;
}

std::string roomOf(const std::string& path) {
    const std::string prefix = "engine/src/";
    if (path.rfind(prefix, 0) != 0) return {};
    const std::size_t slash = path.find('/', prefix.size());
    return slash == std::string::npos ? std::string() : path.substr(prefix.size(), slash - prefix.size());
}

// The public headers through which the host's Vulkan handles cross the API on purpose.
const std::set<std::string> kVulkanPublicHeaders = {
    "engine/include/lantern/ExternalDevice.h", "engine/include/lantern/Window.h",
    "engine/include/lantern/WindowTypes.h", "engine/include/lantern/glfw/GlfwWindow.h"};

bool mayUseVulkan(const std::string& path) {
    return path.rfind("engine/src/gpu/", 0) == 0 || path.rfind("engine/src/glfw/", 0) == 0 ||
           path.rfind("apps/examples/", 0) == 0 || kVulkanPublicHeaders.count(path);
}

// The public headers a file includes that its room may not (or that no room owns). Hosts
// (apps/, benchmarks/) may include any public header.
std::vector<std::string> publicIncludeViolations(const SourceFile& f, const std::string& room) {
    std::vector<std::string> out;
    static const std::regex angled(R"(#\s*include\s*<lantern/([^>]+)>)");
    if (room == "?") return {f.path + ": a public header no room owns (add it to kPublicHeaderRooms)"};
    for (auto it = std::sregex_iterator(f.text.begin(), f.text.end(), angled);
         it != std::sregex_iterator(); ++it) {
        const std::string header = (*it)[1];
        const auto owner = kPublicHeaderRooms.find(header);
        if (owner == kPublicHeaderRooms.end()) {
            out.push_back(f.path + ": includes <lantern/" + header + ">, which no room owns");
            continue;
        }
        if (!room.empty() && !mayInclude(room, owner->second))
            out.push_back(f.path + ": room " + room + " may not include <lantern/" + header +
                          "> (" + owner->second + "'s; dependencies run one way)");
    }
    return out;
}

// Every broken rule of a file, one line each.
std::vector<std::string> violations(const SourceFile& f) {
    std::vector<std::string> out;
    static const std::regex vkCall(R"(\bvk[A-Z]\w*\s*\()");
    static const std::regex vkInclude(R"(#\s*include\s*[<"]vulkan/)");
    static const std::regex quoted(R"re(#\s*include\s*"([^"]+)")re");
    if (!mayUseVulkan(f.path)) {
        std::smatch m;
        if (std::regex_search(f.text, m, vkCall))
            out.push_back(f.path + ": calls Vulkan (" + m.str() + "...) outside engine/src/gpu");
        if (std::regex_search(f.text, vkInclude))
            out.push_back(f.path + ": includes a Vulkan header outside engine/src/gpu");
    }
    const std::string room = publicRoomOf(f.path).empty() ? roomOf(f.path) : publicRoomOf(f.path);
    for (const std::string& v : publicIncludeViolations(f, room)) out.push_back(v);
    if (room.empty() || !publicRoomOf(f.path).empty()) return out;
    const auto allowed = kRoomIncludes.find(room);
    if (allowed == kRoomIncludes.end()) {
        out.push_back(f.path + ": room \"" + room + "\" is not in the architecture's list");
        return out;
    }
    for (auto it = std::sregex_iterator(f.text.begin(), f.text.end(), quoted);
         it != std::sregex_iterator(); ++it) {
        const std::string inc = (*it)[1];
        const std::size_t slash = inc.find('/');
        if (slash == std::string::npos) {
            const auto other = kNonRoomIncludes.find(inc);
            if (other == kNonRoomIncludes.end() || !other->second.count(room))
                out.push_back(f.path + ": room " + room + " may not include \"" + inc + "\"");
            continue;
        }
        const std::string target = inc.substr(0, slash);
        if (target == room) continue;
        if (!allowed->second.count(target)) {
            out.push_back(f.path + ": room " + room + " may not include " + inc +
                          " (dependencies run one way)");
            continue;
        }
        if (target == "gpu" && room != "gpu" && !kGpuInterface.count(inc) &&
            !(inc == "gpu/Presenter.h" && kWindowException.count(f.path)))
            out.push_back(f.path + ": sees gpu/ through " + inc +
                          ", which is not one of its Vulkan-free interface headers");
    }
    return out;
}

std::vector<SourceFile> sourceTree() {
    std::vector<SourceFile> files;
    const std::filesystem::path root = sourceDir();
    for (const char* top : {"engine/src", "engine/include/lantern", "apps", "benchmarks"})
        for (const auto& e : std::filesystem::recursive_directory_iterator(root / top)) {
            const std::string ext = e.path().extension().string();
            if (!e.is_regular_file() || (ext != ".cpp" && ext != ".h" && ext != ".in")) continue;
            std::ifstream in(e.path());
            std::ostringstream text;
            text << in.rdbuf();
            files.push_back({std::filesystem::relative(e.path(), root).generic_string(), text.str()});
        }
    return files;
}

TEST(Architecture, TheSourceTreeKeepsEveryBoundary) {
    const std::vector<SourceFile> files = sourceTree();
    ASSERT_GT(files.size(), 50u) << "the source tree was not found under " << sourceDir();
    std::size_t gpuFiles = 0;
    std::string report;
    for (const SourceFile& f : files) {
        gpuFiles += roomOf(f.path) == "gpu";
        for (const std::string& v : violations(f)) report += v + "\n";
    }
    EXPECT_GT(gpuFiles, 5u);
    // Every public header has its room, and every room of the map exists.
    for (const auto& e : std::filesystem::recursive_directory_iterator(sourceDir() / "engine/include/lantern")) {
        if (!e.is_regular_file()) continue;
        const std::string path = std::filesystem::relative(e.path(), sourceDir()).generic_string();
        EXPECT_NE(publicRoomOf(path), "?") << path;
    }
    for (const auto& [header, room] : kPublicHeaderRooms) EXPECT_TRUE(kRoomIncludes.count(room)) << header;
    EXPECT_TRUE(report.empty()) << report;
}

TEST(Architecture, EveryRoomIsListedAndTheRoomsFormNoCycle) {
    std::set<std::string> rooms;
    for (const auto& e : std::filesystem::directory_iterator(sourceDir() / "engine/src"))
        if (e.is_directory()) rooms.insert(e.path().filename().string());
    for (const std::string& room : rooms) EXPECT_TRUE(kRoomIncludes.count(room)) << room;
    // Depth-first search over the allowed edges: a back edge would be a permitted cycle.
    std::map<std::string, int> state;  // 1: on the stack, 2: done
    std::function<bool(const std::string&)> acyclic = [&](const std::string& r) {
        if (state[r] == 1) return false;
        if (state[r] == 2) return true;
        state[r] = 1;
        for (const std::string& next : kRoomIncludes.at(r))
            if (!acyclic(next)) return false;
        state[r] = 2;
        return true;
    };
    for (const auto& [room, _] : kRoomIncludes) EXPECT_TRUE(acyclic(room)) << room;
}

// The rules fire on files that break them.
TEST(Architecture, TheRulesCatchWhatTheyGuard) {
    struct Case {
        SourceFile file;
        std::size_t expected;
        const char* why;
    };
    const Case cases[] = {
        {{"engine/src/render/X.cpp", "void f(VkCommandBuffer c) { vkCmdDraw(c, 3, 1, 0, 0); }"}, 1,
         "a draw recorded outside gpu/"},
        {{"engine/src/render/X.cpp", "#include <vulkan/vulkan.h>\n"}, 1, "a Vulkan include"},
        {{"engine/src/render/X.cpp", "#include \"gpu/Context.h\"\n"}, 1,
         "gpu's Vulkan internals seen from render/"},
        {{"engine/src/reference/X.cpp", "#include \"render/FrameRender.h\"\n"}, 1,
         "the reference depending on the renderer it checks"},
        {{"engine/src/reference/X.cpp", "#include \"lantern_shared.h\"\n#include \"frame/Frame.h\"\n"},
         0, "the shared constants and the frame model are allowed"},
        {{"engine/src/frame/X.cpp", "#include \"gpu/DrawList.h\"\n"}, 1, "frame/ below gpu/"},
        {{"engine/src/render/X.cpp", "#include \"io/AtomicFile.h\"\n"}, 1,
         "file writing inside the renderer"},
        {{"engine/src/gpu/X.cpp", "#include \"render/Variants.h\"\nvoid f() { vkDeviceWaitIdle(d); }"},
         1, "gpu/ may call Vulkan but not include render/"},
        {{"engine/src/api/X.cpp", "#include \"gpu/Presenter.h\"\n"}, 1,
         "the presenter outside the window API"},
        {{"engine/src/api/WindowTarget.cpp", "#include \"gpu/Presenter.h\"\n"}, 0,
         "the window API's exception"},
        {{"apps/lantern/view/X.cpp", "int f() { return vkGetInstanceProcAddr(0, \"\") != 0; }"}, 1,
         "the viewer calling Vulkan"},
        {{"apps/examples/glfw_window/main.cpp", "void f() { vkDeviceWaitIdle(d); }"}, 0,
         "a host example may"},
        {{"engine/src/newroom/X.cpp", ""}, 1, "a room the rules do not know"},
        {{"engine/src/scene/X.cpp", "#include <lantern/Io.h>\n"}, 1,
         "scene/ calling the loader through the public entry points"},
        {{"engine/src/gpu/X.h", "#include <lantern/Renderer.h>\n"}, 1,
         "gpu/ seeing the renderer's entry points"},
        {{"engine/src/io/X.cpp", "#include <lantern/Renderer.h>\n"}, 1, "io/ seeing the renderer"},
        {{"engine/src/gpu/X.h", "#include <lantern/RenderTypes.h>\n#include <lantern/Scene.h>\n"}, 0,
         "the types any room may hold"},
        {{"engine/src/api/X.cpp", "#include <lantern/Io.h>\n#include <lantern/Renderer.h>\n"}, 0,
         "api/ implements the entry points"},
        {{"engine/include/lantern/Reference.h", "#include <lantern/Renderer.h>\n"}, 1,
         "a public types header of a lower room including an entry point"},
        {{"engine/include/lantern/Unlisted.h", ""}, 1, "a public header no room owns"},
        {{"engine/src/render/X.cpp", "#include <lantern/Missing.h>\n"}, 1,
         "a public header that does not exist"},
        {{"benchmarks/X.cpp", "#include <lantern/Lantern.h>\n#include <lantern/Window.h>\n"}, 0,
         "a benchmark is a host"},
        {{"benchmarks/X.cpp", "void f() { vkDeviceWaitIdle(d); }"}, 1,
         "a benchmark calling Vulkan"},
    };
    for (const Case& c : cases)
        EXPECT_EQ(violations(c.file).size(), c.expected) << c.why << ": " << c.file.path;
}

} // namespace
