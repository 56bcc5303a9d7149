// The options of `lantern render` (docs/cli.md) and what is checked once they are parsed.
#include "common/CliSupport.h"
#include "render/RenderArgs.h"

#include <string>

namespace lantern::cli {
namespace {

// --cryptomatte-levels and --cryptomatte-samples (docs/aovs.md).
void addCryptomatteOptions(CLI::App& cmd, RenderArgs& args) {
    cmd.add_option("--cryptomatte-levels", args.cryptomatteLevels,
                   "Cryptomatte ranks (id, coverage) per pixel: even, 2 to 16, two per EXR layer")
        ->capture_default_str()
        ->check(CLI::Range(2, 16));
    cmd.add_option("--cryptomatte-samples", args.cryptomatteSamples,
                   "Cryptomatte coverage samples per pixel along each axis (N x N), 1 to 16")
        ->capture_default_str()
        ->check(CLI::Range(1, 16));
}

} // namespace

void addRenderOptions(CLI::App& cmd, RenderArgs& args) {
    cmd.add_option("scene", args.scenes,
                   "Scene file (glTF, GLB, OBJ, PLY, STL, OFF), or builtin:NAME; several, a quoted "
                   "glob or @LIST render a batch (docs/sequences.md); required unless --list is "
                   "given");
    cmd.add_option("-o,--output", args.outputs,
                   "Output file(s): .exr or .png, repeat to write several; '#' runs are the "
                   "frame number; missing folders are created (default out/render.exr, "
                   "out/frame_####.exr for a sequence)");
    addSizeOptions(cmd, args.width, args.height);
    cmd.add_option("--scene", args.sceneIndex,
                   "glTF scene index (default: the file's default; 0 to the file's last)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--time", args.time,
                   "Animation time in seconds of the one frame (its number: round(time x fps); "
                   "finite, 0 to 1e9)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e9)); // and not NaN: run() checks
    cmd.add_option("--frame", args.frame, "Render frame N alone, at time N / fps")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--background", args.background, help::kBackground);
    cmd.add_option("--frames", args.frames,
                   "Render the sequence of frames A-B inclusive (frame k at time k/fps)");
    cmd.add_option(
        "--frame-list", args.frameList,
        "Render these frames, not a range: N,A-B,... (--shard splits the list by position)");
    cmd.add_option("--fps", args.fps, "Frames per second: frame k is at time k / fps")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd.add_option("--shard", args.shard, "Render only frames k with k mod N == I (I/N)");
    cmd.add_option("--encoder-threads", args.encoderThreads,
                   "Threads encoding frames (0: one per core; 0 to 256)")
        ->capture_default_str()
        ->check(CLI::Range(0, kMaxEncoderThreads));
    cmd.add_option("--aov", args.aovs,
                   std::string("Extra EXR channels, comma-separated (docs/aovs.md): ") + aovNames())
        ->delimiter(',');
    addCryptomatteOptions(cmd, args);
    cmd.add_flag("--unlit-exact", args.unlitExact,
                 "Exact label colours: every material unlit, its base colour written bit for "
                 "bit (no lighting, texture, blending or anti-aliasing)");
    cmd.add_flag("--write-camera", args.writeCamera,
                 "Write each image's camera beside it as JSON (same name, .json): size, "
                 "intrinsics K, the pose in OpenCV's and glTF's axes, near, far, projection");
    cmd.add_flag("--half", args.half, "Write 16-bit half channels instead of 32-bit float");
    cmd.add_option("--compression", args.compression,
                   "EXR compression: none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab")
        ->capture_default_str();
    cmd.add_option("--zip-level", args.zipLevel,
                   "zlib level of the zip and zips compressions: 1 fastest to 9 smallest")
        ->capture_default_str()
        ->check(CLI::Range(1, 9));
    cmd.add_flag("--dry-run", args.dryRun,
                 "Check the options and load the scene, print what would be written, and stop: "
                 "no device is created and no file or folder is written");
    cmd.add_flag("--explain", args.explain,
                 "Print the features the scene uses and the pipeline variants");
    cmd.add_option("--probe", args.probe,
                   "X,Y: print the lighting equation term by term at pixel X,Y (x from the left, "
                   "y from the top)");
    args.file.add(cmd);
    cmd.add_option("--report", args.report,
                   "Write the fidelity report as JSON to FILE: every feature the file uses, "
                   "supported, approximated (the rule) or skipped, and its objects");
    args.camera.add(cmd);
    args.shading.add(cmd);
    args.device.add(cmd);
    cmd.add_option("--compare", args.compareRef,
                   "Compare the picture with this reference (.exr or .png) as `lantern compare` "
                   "does, with its thresholds; exit 1 when it fails");
    args.compare.add(cmd);
    args.batch.add(cmd);
}

Result<void> takeParsedRenderOptions(const CLI::App& cmd, RenderArgs& args) {
    args.timeGiven = cmd.count("--time") > 0;
    args.frameGiven = cmd.count("--frame") > 0;
    args.widthGiven = cmd.count("--width") > 0;
    args.heightGiven = cmd.count("--height") > 0;
    if (args.scenes.empty() && args.batch.lists.empty())
        return makeError(ErrorCode::Usage, "give a scene (or --list FILE)", "scene");
    // An empty value is a forgotten one, not "no sequence": `--frames ""` rendered frame 0.
    for (const char* option : {"--frames", "--frame-list"})
        if (cmd.count(option) > 0 && cmd.get_option(option)->as<std::string>().empty())
            return makeError(ErrorCode::Usage,
                             std::string("needs a value (") +
                                 (option[7] == '-' ? "N,A-B,..." : "A-B") +
                                 "); it was given an empty one",
                             option);
    return {};
}

} // namespace lantern::cli
