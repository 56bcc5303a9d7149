// The pipeline cache kept on disk between runs (gpu/PipelineCache.h): a second renderer loads
// what the first wrote; a damaged, truncated or foreign file, or a link planted at its name,
// is refused with one warning naming the file and the reason, and replaced, without following
// the link; a folder that cannot be written is a warning; turned off, nothing is read or
// written; and the missing variants of a frame, compiled together, render what one renderer
// compiling them one by one renders. Each test keeps its cache in its own folder.
#include "TestSupport.h"

#include "gpu/Context.h"
#include "gpu/PipelineCache.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <mutex>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>

namespace {

using namespace lantern;
namespace fs = std::filesystem;
using test::testOutputDir;

std::vector<std::uint8_t> readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, std::span<const std::uint8_t> bytes) {
    std::ofstream(p, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Sets an environment variable for one test and puts the old value back.
class EnvGuard {
public:
    EnvGuard(const char* name, const char* value) : m_name(name) {
        if (const char* old = std::getenv(name)) m_old = old;
        if (value) ::setenv(name, value, 1);
        else ::unsetenv(name);
    }
    ~EnvGuard() {
        if (m_old) ::setenv(m_name, m_old->c_str(), 1);
        else ::unsetenv(m_name);
    }

private:
    const char* m_name;
    std::optional<std::string> m_old;
};

// The warnings a renderer logs (its sink outlives it: the cache is written on destruction).
struct Warnings {
    std::mutex mutex;
    std::vector<std::string> lines;
    LogSink sink() {
        return [this](LogLevel level, std::string_view message) {
            if (level < LogLevel::Warning) return;
            std::lock_guard lock(mutex);
            lines.emplace_back(message);
        };
    }
    std::string all() {
        std::lock_guard lock(mutex);
        std::string out;
        for (const std::string& l : lines) out += l + "\n";
        return out;
    }
};

class PipelineCache_ : public test::GpuTest {
protected:
    // The properties of the device every renderer here chooses (the shared device's).
    const VkPhysicalDeviceProperties& props() { return device().context().properties(); }

    Result<Renderer> make(const fs::path& folder, Warnings& warnings) {
        RendererDesc desc;
        desc.validation = true;
        desc.pipelineCacheFolder = folder.string();
        desc.log = warnings.sink();
        return Renderer::create(desc);
    }

    // One small frame of a scene that needs a few variants; it must draw and be clean.
    void renderOnce(Renderer& r) {
        auto scene = builtinScene("spheres");
        ASSERT_TRUE(scene) << scene.error().describe();
        RenderOptions o;
        o.width = 32;
        o.height = 24;
        auto img = r.render(*scene, o, 0.0);
        ASSERT_TRUE(img) << img.error().describe();
        EXPECT_GT(test::countCovered(*img), 0u);
        EXPECT_EQ(r.validationMessageCount(), 0u);
    }

    // Renders once with a fresh renderer caching in `folder`; the file it wrote.
    fs::path warmUp(const fs::path& folder) {
        Warnings w;
        fs::path file;
        {
            auto r = make(folder, w);
            EXPECT_TRUE(r) << r.error().describe();
            if (!r) return {};
            renderOnce(*r);
            file = r->device().pipelineCacheFile;
        }  // the renderer goes: the file is written
        EXPECT_EQ(w.all(), "");
        return file;
    }

    // The driver's data in `file` when it is valid for this device ("" in `why`).
    std::size_t validData(const fs::path& file, std::string& why) {
        const std::vector<std::uint8_t> bytes = readBytes(file);
        return gpu::pipelineCacheData(bytes, props(), why).size();
    }
};

TEST_F(PipelineCache_, ASecondRendererLoadsWhatTheFirstWrote) {
    const fs::path folder = testOutputDir() / "cache" / "lantern";
    const fs::path file = warmUp(folder);
    ASSERT_EQ(file, gpu::pipelineCachePlace({true, folder.string()}, props()).file);
    ASSERT_EQ(file.parent_path(), folder);
    struct stat st {};
    ASSERT_EQ(::stat(folder.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0700u) << "the cache folder is the user's alone";
    ASSERT_EQ(::lstat(file.c_str(), &st), 0) << file;
    ASSERT_TRUE(S_ISREG(st.st_mode));
    const ino_t written = st.st_ino;
    std::string why;
    const std::size_t data = validData(file, why);
    ASSERT_GT(data, 0u) << why;

    Warnings w;
    {
        auto second = make(folder, w);
        ASSERT_TRUE(second) << second.error().describe();
        EXPECT_EQ(second->device().pipelineCacheFile, file.string());
        EXPECT_EQ(second->device().pipelineCacheLoadedBytes, data)
            << "the cache was created with the file's data";
        renderOnce(*second);
    }
    EXPECT_EQ(w.all(), "");
    // The same pipelines again: the driver's data did not change, so the file was not written.
    ASSERT_EQ(::lstat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_ino, written);
}

TEST_F(PipelineCache_, ARefusedFileIsNamedInOneWarningAndReplaced) {
    const fs::path folder = testOutputDir() / "cache";
    const fs::path file = warmUp(folder);
    const std::vector<std::uint8_t> good = readBytes(file);
    ASSERT_GE(good.size(), 32u + sizeof(VkPipelineCacheHeaderVersionOne));
    const std::vector<std::uint8_t> data(good.begin() + 32, good.end());
    std::vector<std::uint8_t> foreign = data;  // another device's cache UUID, well formed
    foreign[offsetof(VkPipelineCacheHeaderVersionOne, pipelineCacheUUID)] ^= 0xff;
    std::vector<std::uint8_t> flipped = good;  // one byte of the driver's data changed
    flipped.back() ^= 0x01;
    std::vector<std::uint8_t> random(300);
    for (std::size_t i = 0; i < random.size(); ++i) random[i] = std::uint8_t(i * 131 + 7);

    const struct {
        const char* name;
        std::vector<std::uint8_t> bytes;
        const char* reason;
    } cases[] = {
        {"random bytes", random, "not a Lantern pipeline cache"},
        {"another device", gpu::pipelineCacheFileBytes(foreign), "made by another device"},
        {"truncated", {good.begin(), good.end() - 5}, "truncated"},
        {"header only", {good.begin(), good.begin() + 20}, "truncated"},
        {"damaged", flipped, "damaged: the checksum"},
        {"empty", {}, "truncated"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        writeBytes(file, c.bytes);
        Warnings w;
        {
            auto r = make(folder, w);
            ASSERT_TRUE(r) << r.error().describe();
            EXPECT_EQ(r->device().pipelineCacheLoadedBytes, 0u);
            renderOnce(*r);
        }
        ASSERT_EQ(w.lines.size(), 1u) << w.all();
        EXPECT_NE(w.lines[0].find(file.string()), std::string::npos) << w.lines[0];
        EXPECT_NE(w.lines[0].find(c.reason), std::string::npos) << w.lines[0];
        EXPECT_NE(w.lines[0].find("it will be replaced"), std::string::npos) << w.lines[0];
        std::string why;
        EXPECT_GT(validData(file, why), 0u) << "replaced by a valid file: " << why;
    }
}

TEST_F(PipelineCache_, ALinkAtTheFileNameIsNotFollowed) {
    const fs::path dir = testOutputDir();
    const fs::path folder = dir / "cache";
    fs::create_directories(folder);
    const fs::path file = gpu::pipelineCachePlace({true, folder.string()}, props()).file;
    const fs::path target = dir / "precious.txt";
    std::ofstream(target) << "not the cache's to overwrite\n";
    fs::create_symlink(target, file);

    Warnings w;
    {
        auto r = make(folder, w);
        ASSERT_TRUE(r) << r.error().describe();
        EXPECT_EQ(r->device().pipelineCacheLoadedBytes, 0u);
        renderOnce(*r);
    }
    ASSERT_EQ(w.lines.size(), 1u) << w.all();
    EXPECT_NE(w.lines[0].find(file.string() + ": it is a symbolic link, which is not followed"),
              std::string::npos)
        << w.lines[0];
    std::ifstream in(target);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}),
              "not the cache's to overwrite\n");
    EXPECT_EQ(fs::symlink_status(file).type(), fs::file_type::regular)
        << "the link itself was replaced";
    std::string why;
    EXPECT_GT(validData(file, why), 0u) << why;
}

TEST_F(PipelineCache_, AFolderThatCannotBeWrittenIsAWarning) {
    const fs::path dir = testOutputDir();
    std::ofstream(dir / "a-file") << "x";
    // Even root cannot make a folder inside a regular file.
    std::vector<fs::path> folders = {dir / "a-file" / "cache"};
    if (::geteuid() != 0) {
        fs::create_directories(dir / "read-only");
        fs::permissions(dir / "read-only", fs::perms::owner_read | fs::perms::owner_exec);
        folders.push_back(dir / "read-only");
    }
    for (const fs::path& folder : folders) {
        SCOPED_TRACE(folder.string());
        Warnings w;
        {
            auto r = make(folder, w);
            ASSERT_TRUE(r) << r.error().describe();
            renderOnce(*r);
        }
        ASSERT_EQ(w.lines.size(), 1u) << w.all();
        EXPECT_NE(w.lines[0].find("pipeline cache " + folder.string()), std::string::npos)
            << w.lines[0];
        EXPECT_NE(w.lines[0].find("not written"), std::string::npos) << w.lines[0];
    }
    std::error_code ignored;  // absent when running as root
    fs::permissions(dir / "read-only", fs::perms::owner_all, ignored);
}

TEST_F(PipelineCache_, TurnedOffNothingIsReadOrWritten) {
    const fs::path dir = testOutputDir();
    {
        EnvGuard off("LANTERN_PIPELINE_CACHE", "0");
        Warnings w;
        {
            auto r = make(dir / "by-environment", w);
            ASSERT_TRUE(r) << r.error().describe();
            EXPECT_EQ(r->device().pipelineCacheFile, "");
            renderOnce(*r);
        }
        EXPECT_EQ(w.all(), "");
        EXPECT_FALSE(fs::exists(dir / "by-environment"));
    }
    RendererDesc desc;
    desc.validation = true;
    desc.pipelineCacheOnDisk = false;
    desc.pipelineCacheFolder = (dir / "by-the-host").string();
    {
        auto r = Renderer::create(desc);
        ASSERT_TRUE(r) << r.error().describe();
        EXPECT_EQ(r->device().pipelineCacheFile, "");
        renderOnce(*r);
    }
    EXPECT_FALSE(fs::exists(dir / "by-the-host"));
}

// The missing variants of one frame are compiled on several threads at once: exactly those the
// draws use, and the frame is the shared renderer's (whose variants exist already) bit for bit.
TEST_F(PipelineCache_, VariantsCompiledTogetherRenderAsOneByOne) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene) << scene.error().describe();
    RenderOptions o;
    o.width = 48;
    o.height = 32;
    o.aovs.normal = true;  // with --msaa, the AOV pass adds its own variants
    o.msaa = 4;
    auto variants = explainScene(*scene, o);
    ASSERT_TRUE(variants) << variants.error().describe();
    // Each variant and its single-sample AOV twin: at least two, made at once.
    const std::size_t expected = 2 * variants->variants.size();
    ASSERT_GE(expected, 2u);

    RendererDesc desc;
    desc.validation = true;
    desc.pipelineCacheOnDisk = false;
    auto fresh = Renderer::create(desc);
    ASSERT_TRUE(fresh) << fresh.error().describe();
    auto together = fresh->render(*scene, o, 0.0);
    ASSERT_TRUE(together) << together.error().describe();
    EXPECT_EQ(fresh->lastFrameStats().pipelinesCreated, expected) << "and nothing else";
    EXPECT_EQ(fresh->validationMessageCount(), 0u);

    auto alone = renderer().render(*scene, o, 0.0);
    ASSERT_TRUE(alone) << alone.error().describe();
    EXPECT_GT(test::countCovered(*together), 0u);
    EXPECT_EQ(together->rgba, alone->rgba) << test::saveComparison(*together, *alone, "variants");
}

// Where the file goes, without a device: LANTERN_CACHE_DIR, else an absolute XDG_CACHE_HOME,
// else ~/.cache; the name changes with the device and the driver.
TEST(PipelineCacheFile, TheFolderAndNameFollowTheEnvironmentDeviceAndDriver) {
    VkPhysicalDeviceProperties p{};
    p.vendorID = 0x10005;
    p.deviceID = 7;
    p.driverVersion = 42;
    EnvGuard noSwitch("LANTERN_PIPELINE_CACHE", nullptr);
    EnvGuard home("HOME", "/home/someone");
    {
        EnvGuard cache("LANTERN_CACHE_DIR", "/lantern-cache");
        EnvGuard xdg("XDG_CACHE_HOME", "/xdg");
        EXPECT_EQ(gpu::pipelineCachePlace({}, p).file.parent_path(), "/lantern-cache");
        EXPECT_EQ(gpu::pipelineCachePlace({true, "/host"}, p).file.parent_path(), "/host");
    }
    EnvGuard cache("LANTERN_CACHE_DIR", nullptr);
    {
        EnvGuard xdg("XDG_CACHE_HOME", "/xdg");
        EXPECT_EQ(gpu::pipelineCachePlace({}, p).file.parent_path(), "/xdg/lantern");
    }
    {
        EnvGuard xdg("XDG_CACHE_HOME", "relative");  // the XDG specification ignores it
        EXPECT_EQ(gpu::pipelineCachePlace({}, p).file.parent_path(),
                  "/home/someone/.cache/lantern");
    }
    EnvGuard xdg("XDG_CACHE_HOME", nullptr);
    const fs::path name = gpu::pipelineCachePlace({}, p).file;
    EXPECT_EQ(name.parent_path(), "/home/someone/.cache/lantern");
    EXPECT_EQ(name.filename().string().rfind("pipelines-", 0), 0u) << name;
    VkPhysicalDeviceProperties other = p;
    other.driverVersion = 43;
    EXPECT_NE(gpu::pipelineCachePlace({}, other).file, name);
    other = p;
    other.pipelineCacheUUID[3] = 1;
    EXPECT_NE(gpu::pipelineCachePlace({}, other).file, name);
    {
        EnvGuard off("LANTERN_PIPELINE_CACHE", "0");
        const gpu::PipelineCachePlace place = gpu::pipelineCachePlace({}, p);
        EXPECT_TRUE(place.file.empty());
        EXPECT_EQ(place.off, "LANTERN_PIPELINE_CACHE=0");
    }
}

} // namespace
