// ViewArgs.h: the options of `lantern view` as its command line gave them (ViewCommand.cpp
// declares them; the Viewer starts from them).
#pragma once

#include "common/CliSupport.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::cli {

struct ViewArgs {
    std::string scene;
    int width = 1280, height = 720;
    int sceneIndex = -1;
    double time = 0.0;
    bool paused = false;
    double fps = 24.0;
    std::string presentMode = "fifo";
    int framesInFlight = 2;
    bool watch = false;
    std::vector<std::string> screenshots;
    int afterFrames = 0;
    std::string screenshotDir = ".";
    bool noPanel = false, showHelp = false, stats = false;
    bool headlight = false, wireframe = false, normals = false;
    std::string background;
    SceneFileOptions file;  ///< --max-size, --variant, --allow-folder, --up
    CameraOptions camera;
    ShadingOptions shading;
    DeviceOptions device;
};

} // namespace lantern::cli
