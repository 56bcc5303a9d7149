// The run of a batch (Batch.h): one renderer and device for every job; each scene loaded,
// prepared, rendered from its views and released before the next; finished outputs skipped;
// a scene or job that fails is reported and the batch goes on.
#include "render/Batch.h"

#include "common/CliSupport.h"
#include <lantern/CameraConventions.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <sys/stat.h>

namespace lantern::cli {
namespace {


// A job is finished when every output exists as a regular file: writers rename complete files
// into place (io/AtomicFile), so an output that exists is whole.
bool finished(const BatchJob& job) {
    for (const std::string& out : job.outputs) {
        struct stat st {};
        if (::stat(out.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
    }
    return true;
}

struct Tally {
    std::size_t rendered = 0, skipped = 0, failed = 0;
    std::vector<std::string> failedScenes;  // in order, each once
    bool deviceLost = false;
};

void fail(Tally& t, const BatchScene& scene, const Error& error, std::size_t jobs) {
    report(error);
    t.failed += jobs;
    if (t.failedScenes.empty() || t.failedScenes.back() != scene.path)
        t.failedScenes.push_back(scene.path);
    t.deviceLost = t.deviceLost || error.code == ErrorCode::DeviceLost;
}

// One job: render the view at the frame, write every output (its path on stdout).
Result<void> renderJob(const BatchRequest& r, Renderer& renderer, const PreparedScene& prepared,
                       const BatchView& view, const BatchFrame& frame, const BatchJob& job) {
    RenderOptions options = r.options;
    if (view.camera) {
        options.camera = *view.camera;
        options.views.clear();
    }
    auto image = renderer.render(prepared, options, frame.time);
    if (!image) return std::move(image).error();
    for (const std::string& out : job.outputs) {
        const std::filesystem::path parent = std::filesystem::path(out).parent_path();
        std::error_code ec;
        if (!parent.empty() && !std::filesystem::create_directories(parent, ec) && ec)
            return makeError(ErrorCode::IoError,
                             "cannot create the folder " + parent.string() + ": " + ec.message(),
                             "--output", out);
        std::uint64_t clamped = 0;
        ExrOptions exr = r.exr;
        exr.clampedCount = &clamped;
        // The camera first: a finished image always has its camera beside it.
        if (r.writeCamera) LANTERN_TRY(writeImageCamera(out, *image));
        LANTERN_TRY(writeImage(out, *image, exr));
        if (clamped > 0)
            std::cerr << "lantern: warning: " << out << ": " << clamped
                      << " values exceeded the half range and were clamped to 65504\n";
        std::cout << out + "\n" << std::flush;  // one write: whole lines when processes share stdout
    }
    return {};
}

// The jobs of one scene (all of this shard's that are not finished): load, prepare, render
// each, release.
void runScene(const BatchRequest& r, Renderer& renderer, const BatchScene& scene,
              const std::vector<BatchView>& views, const std::vector<const BatchJob*>& jobs,
              Tally& t) {
    if (scene.problem) return fail(t, scene, *scene.problem, jobs.size());
    auto loaded = loadScene(scene.path, r.load);
    if (!loaded) return fail(t, scene, loaded.error(), jobs.size());
    auto shared = std::make_shared<const Scene>(std::move(*loaded));
    if (auto why = nothingToDraw(*shared, r.options.root))
        std::cerr << "lantern: warning: " << scene.path << ": nothing to draw (" << *why
                  << "); the image is the background\n";
    auto prepared = renderer.prepare(shared);
    if (!prepared) return fail(t, scene, prepared.error(), jobs.size());
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        if (stopSignal() != 0 || t.deviceLost) return;
        const BatchJob& job = *jobs[i];
        auto done = renderJob(r, renderer, *prepared, views[job.view], r.frames[job.frame], job);
        if (done) {
            ++t.rendered;
        } else {
            Error e = std::move(done).error();
            if (e.file.empty()) e.file = scene.path;
            e.object = "view " + views[job.view].name + (e.object.empty() ? "" : ": " + e.object);
            fail(t, scene, e, 1);
        }
    }
}

void printDryRun(const std::vector<BatchScene>& scenes, const std::vector<const BatchJob*>& mine,
                 const std::vector<bool>& skip) {
    for (std::size_t i = 0; i < mine.size(); ++i)
        for (const std::string& out : mine[i]->outputs)
            std::cout << (skip[i] ? "  would skip " : "  would write ") << out << " ("
                      << scenes[mine[i]->scene].path << ")\n";
}

} // namespace

int runBatch(const BatchRequest& r) {
    auto scenes = expandScenes(r.scenes, r.lists, r.load.allowedFolders, r.load.maxBytes);
    if (!scenes) return report(scenes.error());
    auto views = parseViews(r.views, r.load.maxBytes);
    if (!views) return report(views.error());
    auto jobs = planJobs(*scenes, *views, r.frames, r.outputs);
    if (!jobs) return report(jobs.error());

    // This shard's jobs (position k with k mod N == I, in the batch's fixed order) and which
    // of them are finished already.
    std::vector<const BatchJob*> mine;
    for (std::size_t k = 0; k < jobs->size(); ++k)
        if (!r.shard || int(k % std::size_t(r.shard->count)) == r.shard->index)
            mine.push_back(&(*jobs)[k]);
    std::vector<bool> skip(mine.size());
    Tally t;
    for (std::size_t i = 0; i < mine.size(); ++i) {
        skip[i] = !r.overwrite && finished(*mine[i]);
        t.skipped += skip[i];
    }
    const std::string shape = std::to_string(scenes->size()) + " scenes x " +
                              std::to_string(views->size()) + " views x " +
                              std::to_string(r.frames.size()) + " frames" +
                              (r.shard ? ", shard " + std::to_string(r.shard->index) + "/" +
                                             std::to_string(r.shard->count)
                                       : "");
    if (r.dryRun) {
        std::cout << "dry run: batch of " << mine.size() << " jobs (" << shape << "), "
                  << mine.size() - t.skipped << " to render, " << t.skipped << " finished\n";
        printDryRun(*scenes, mine, skip);
        return kOk;
    }

    const auto start = std::chrono::steady_clock::now();
    auto renderer = Renderer::create(r.device);
    if (!renderer) return report(renderer.error());
    if (r.verbose)
        std::cerr << "lantern: device: " << renderer->device().name << " ("
                  << renderer->device().driver << ")\n";
    if (r.checkDevice)
        if (auto c = r.checkDevice(renderer->device()); !c) return report(c.error());
    installStopHandlers();  // stops between two jobs
    for (std::size_t s = 0; s < scenes->size(); ++s) {
        std::vector<const BatchJob*> pending;
        for (std::size_t i = 0; i < mine.size(); ++i)
            if (mine[i]->scene == s && !skip[i]) pending.push_back(mine[i]);
        if (pending.empty()) continue;
        if (stopSignal() != 0 || t.deviceLost) break;
        runScene(r, *renderer, (*scenes)[s], *views, pending, t);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr,
                 "lantern: batch: %zu rendered, %zu skipped, %zu failed of %zu jobs (%s) in "
                 "%.2f s (%.2f renders/s)\n",
                 t.rendered, t.skipped, t.failed, mine.size(), shape.c_str(), seconds,
                 seconds > 0 ? double(t.rendered) / seconds : 0.0);
    for (const std::string& f : t.failedScenes)
        std::fprintf(stderr, "lantern: batch: failed: %s\n", f.c_str());
    if (const int sig = stopSignal(); sig != 0) {
        std::fprintf(stderr, "lantern: stopped by %s; the outputs written are complete\n",
                     sig == SIGTERM ? "SIGTERM" : "SIGINT");
        return 128 + sig;
    }
    if (t.deviceLost) return kFailed;
    return t.failed > 0 ? kRefused : kOk;
}

} // namespace lantern::cli
