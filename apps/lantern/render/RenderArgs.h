// RenderArgs.h: the options of `lantern render` as parsed (render/RenderCli.cpp) for
// RenderCommand.cpp.
#pragma once

#include "common/CliSupport.h"
#include "common/CompareCli.h"
#include "common/CvCameraCli.h"
#include "render/Batch.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::cli {

// The instant one frame is rendered at and its frame number (for the '#' runs of its outputs).
struct SingleFrame {
    double time = 0.0;
    int number = 0;
};

struct RenderArgs {
    std::vector<std::string> scenes;  // one, or a batch's paths, globs and @lists
    BatchCliArgs batch;               // --list, --views, --overwrite (render/Batch.h)
    std::vector<std::string> outputs;
    int width = 1280, height = 720;
    bool widthGiven = false, heightGiven = false;  // a camera file's size applies otherwise
    bool writeCamera = false;  // --write-camera: each image's camera JSON beside it
    int sceneIndex = -1;
    double time = 0.0;
    bool timeGiven = false;
    int frame = 0;           // --frame N: the frame at time N / fps
    bool frameGiven = false;
    std::vector<std::string> aovs;
    int cryptomatteLevels = 4;   // --cryptomatte-levels: ranks per pixel
    int cryptomatteSamples = 4;  // --cryptomatte-samples: N x N per pixel
    bool unlitExact = false;
    bool half = false;
    bool explain = false;
    bool dryRun = false;  // --dry-run: check everything, render and write nothing
    std::string probe;
    std::string compression = "zip";
    int zipLevel = ExrOptions{}.zipLevel;
    SceneFileOptions file;  ///< --max-size, --variant, --allow-folder, --up
    std::string report;     ///< --report FILE: the fidelity report
    std::string background;
    std::string frames;
    std::string frameList; // --frame-list: explicit frames, e.g. those a farm job is missing
    double fps = 24.0;
    std::string shard;
    int encoderThreads = 0;
    CameraOptions camera;
    ShadingOptions shading;
    DeviceOptions device;
    std::string compareRef;     // --compare REF: compare the picture with REF
    CompareCliOptions compare;  // its thresholds (common/CompareCli.h)
};

/// Adds render's options to `cmd`, parsed into `args` (render/RenderCli.cpp).
void addRenderOptions(CLI::App& cmd, RenderArgs& args);

/// Once parsed: notes which options were given and refuses what CLI11 cannot (no scene, an
/// empty --frames or --frame-list: usage errors).
Result<void> takeParsedRenderOptions(const CLI::App& cmd, RenderArgs& args);

} // namespace lantern::cli
