// FrameRender.h: the renderer's core on a gpu::Device: options checked against the device,
// a frame built (frame/) and packed into a draw list (render/DrawLists.h), submitted and read
// back; and on top of that, --explain and --probe. The public lantern::Renderer
// (api/Renderer.cpp) and the engine's own tests use it.
#pragma once

#include "frame/Frame.h"
#include "gpu/Device.h"
#include "gpu/DrawList.h"

#include <lantern/Options.h>
#include <lantern/Probe.h>
#include <lantern/RenderTypes.h>

#include <functional>
#include <memory>

namespace lantern::render {

/// Refuses options the device cannot honour, before anything is allocated.
Result<void> checkOptions(const gpu::Device& device, const RenderOptions& options);

/// A frame and its draw list.
struct PlannedFrame {
    frame::Frame frame;
    gpu::DrawList list;
};
Result<PlannedFrame> planFrame(const Scene& scene, const RenderOptions& options, double time);

/// A frame rendered and read back, with what it was made of.
struct RenderedFrame {
    frame::Frame frame;
    gpu::FrameReadback readback;
};

/// Hooks for the engine's own tests: change the frame or the draw list before submission
/// (to inject what validation refuses, or a wrong pipeline variant).
struct FrameEdits {
    std::function<void(frame::Frame&)> frame;
    std::function<void(gpu::DrawList&)> list;
};

/// Renders synchronously: waits for any slot still in flight, submits, collects (into
/// `storage`'s memory when given; with `inPlace`, the colour is left where it lies and the
/// readback's view says where, gpu::Device::collect). `stats` receives the frame's measurements.
Result<RenderedFrame> renderFrame(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                                  const Scene& sceneData, const RenderOptions& options, double time,
                                  FrameStats& stats, const FrameEdits& edits = {},
                                  Image storage = {}, bool inPlace = false);

/// One band of a picture rendered by renderBands: its readback (collected in place) and the
/// picture row it starts at. The view is valid during the call only.
using BandSink = std::function<Result<void>(const gpu::FrameReadback& band, int top)>;

/// The band height renderBands picks for a width x height picture whose draws process
/// `vertices` vertices: rows of about 4 MiB of float colour (at least 16) when the picture has
/// at least 2^20 pixels and drawing the geometry once more per band costs at most a quarter of
/// a vertex per pixel; otherwise the picture's height (one band).
int autoBandRows(int width, int height, double vertices);

/// Renders the picture in horizontal bands of `rows` rows (0: autoBandRows), top first, each
/// a frame of its own in the device's ring, so band k+1 renders while `sink` reads band k.
/// Only the ring's bands of pixels exist at a time. Colour only (no AOVs). A band holding NaN
/// or Inf fails as nonFiniteFrame, at its pixel in the picture; a failing sink stops the loop
/// with its error. The ring is drained before returning either way.
Result<void> renderBands(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                         const Scene& sceneData, const RenderOptions& options, double time,
                         int rows, FrameStats& stats, const BandSink& sink);

/// The Cryptomatte layers `options.aovs` asks for, for the options.width x options.height
/// picture at `time`: a second, synchronous render of the ids at cryptomatteSamples times the
/// size (render/Cryptomatte.h), counted. Fails as a render would, the message prefixed with
/// what the id render was (an enlarged size the device refuses, typically).
Result<std::vector<CryptomatteLayer>> renderCryptomatte(
    gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene, const Scene& sceneData,
    const RenderOptions& options, double time);

/// The refusal of a frame whose readback held NaN or Inf (never written to a file): exit 3,
/// with the count, the first such pixel and the object drawn there (found by probing it);
/// `frameNumber` names the frame of a sequence.
Error nonFiniteFrame(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                     const Scene& sceneData, const RenderOptions& options, double time,
                     const gpu::FrameReadback& readback, int frameNumber = -1);

/// The features `scene` needs under `options` and the pipeline variants chosen for them.
Result<FeatureReport> explain(const Scene& scene, const RenderOptions& options, double time);

/// Renders once (one sample per pixel, AOVs on) and explains pixel (x, y) with the reference.
Result<ProbeReport> probe(gpu::Device& device, const std::shared_ptr<gpu::SceneBuffers>& scene,
                          const Scene& sceneData, const RenderOptions& options, double time, int x,
                          int y, FrameStats& stats);

} // namespace lantern::render
