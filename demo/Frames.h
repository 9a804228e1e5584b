#pragma once
// What the demo does with its frames: file names, a progress bar for headless runs, a video
// through ffmpeg, and the field's maps exported for artists.

#include "hfx/tools/ImageFiles.h"
#include "hfx/core/SurfaceTextures.h"

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace hfx::demo {

/// DIR/SCENE_0007.EXT (png, jpg or exr: writeImage picks the format by extension)
std::string framePath(const std::string& dir, const std::string& scene, int frame, const std::string& ext = "png");

/// "[#####.....]  12/30 frames  3.2 fps  ETA 6 s" on stderr, redrawn in place.
class Progress {
public:
    Progress(int total, bool enabled);
    void step(int done);
    void finish();
    bool enabled() const { return enabled_; }

private:
    int total_;
    bool enabled_;
    std::chrono::steady_clock::time_point start_;
};

/// Makes the folder DIR (and its parents) for OPTION's files; throws hfx::Error naming the option,
/// the folder and why when it cannot (a file in its place, no permission).
void makeFolder(const std::string& dir, const char* option);

/// Throws hfx::Error saying what to install when ffmpeg is not on the PATH.
void checkVideoEncoder();

/// Pipes RGB frames into ffmpeg (H.264 in whatever container the file name says).
class VideoWriter {
public:
    VideoWriter(const std::string& path, int width, int height, double fps);
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;
    void write(const Image& frame);
    /// Waits for ffmpeg; throws hfx::Error when it failed.
    void close();

private:
    std::string path_;
    int width_, height_;
    std::FILE* pipe_ = nullptr;
    std::vector<unsigned char> rgb_; ///< one frame's bytes, reused frame after frame
};

/// Writes height.exr (float), height.png (8-bit), normal.exr (tangent-space xyz), normal.png
/// (encoded 0.5 + 0.5 n, OpenGL convention) and albedo.png of the textures' level 0.
void exportMaps(const std::string& dir, const SurfaceTextures& textures);

} // namespace hfx::demo
