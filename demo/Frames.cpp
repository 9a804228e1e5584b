#include "Frames.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace hfx::demo {

std::string framePath(const std::string& dir, const std::string& scene, int frame, const std::string& ext) {
    char name[96];
    std::snprintf(name, sizeof name, "%s_%04d.%s", scene.c_str(), frame, ext.c_str());
    return (std::filesystem::path(dir) / name).string();
}

Progress::Progress(int total, bool enabled)
    : total_(total), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

void Progress::step(int done) {
    if (!enabled_) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double fps = seconds > 0.0 ? done / seconds : 0.0;
    const double eta = fps > 0.0 ? (total_ - done) / fps : 0.0;
    constexpr int kWidth = 30;
    const int filled = total_ > 0 ? done * kWidth / total_ : kWidth;
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = '\0';
    std::fprintf(stderr, "\r[%s] %d/%d frames  %.1f fps  ETA %.0f s ", bar, done, total_, fps, eta);
    std::fflush(stderr);
}

void Progress::finish() {
    if (enabled_) std::fprintf(stderr, "\n");
}

void makeFolder(const std::string& dir, const char* option) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (!error && !std::filesystem::is_directory(dir, error))
        error = std::make_error_code(std::errc::not_a_directory);
    if (error) throw Error(str(option, ": cannot make the folder '", dir, "': ", error.message()));
}

void checkVideoEncoder() {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
        throw Error("--video needs ffmpeg on the PATH (Debian: apt-get install ffmpeg)");
}

namespace {
std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}
} // namespace

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
    if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty())
        makeFolder(parent.string(), "--video");
    char header[160];
    std::snprintf(header, sizeof header, "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -s %dx%d -r %.6g -i - ",
                  width, height, fps);
    // Even sizes for yuv420p; the encoder pads odd ones by a pixel.
    const std::string command = std::string(header) +
                                "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p " +
                                shellQuote(path);
    pipe_ = popen(command.c_str(), "w");
    if (!pipe_) throw Error(str("cannot start ffmpeg for '", path, "'"));
}

VideoWriter::~VideoWriter() {
    if (pipe_) pclose(pipe_);
}

void VideoWriter::write(const Image& frame) {
    if (frame.width != width_ || frame.height != height_ || frame.channels != 3)
        throw Error(str("video frame is ", frame.width, "x", frame.height, "x", frame.channels, ", expected ", width_,
                        "x", height_, "x3"));
    rgb_.resize(frame.pixels.size());
    for (size_t i = 0; i < rgb_.size(); ++i)
        rgb_[i] = static_cast<unsigned char>(std::clamp(frame.pixels[i], 0.0f, 1.0f) * 255.0f + 0.5f);
    if (std::fwrite(rgb_.data(), 1, rgb_.size(), pipe_) != rgb_.size())
        throw Error(str("ffmpeg stopped taking frames for '", path_, "'"));
}

void VideoWriter::close() {
    if (!pipe_) return;
    const int status = pclose(pipe_);
    pipe_ = nullptr;
    if (status != 0) throw Error(str("ffmpeg failed writing '", path_, "' (exit status ", status, ")"));
}

void exportMaps(const std::string& dir, const SurfaceTextures& textures) {
    makeFolder(dir, "--export-maps");
    const int w = textures.config().width, h = textures.config().height;
    std::vector<float> surface(size_t(w) * h * 4);
    glGetTextureImage(textures.surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(surface.size() * sizeof(float)), surface.data());
    std::vector<unsigned char> albedo(size_t(w) * h * 4);
    glGetTextureImage(textures.albedo(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(albedo.size()), albedo.data());
    Image height{w, h, 1, std::vector<float>(size_t(w) * h)};
    Image normal{w, h, 3, std::vector<float>(size_t(w) * h * 3)};
    Image encoded = normal, color = normal;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t texel = size_t(y) * w + x; // GL rows: bottom first
            const int row = h - 1 - y;              // image rows: top first
            height.at(x, row, 0) = surface[texel * 4 + 3];
            for (int c = 0; c < 3; ++c) {
                normal.at(x, row, c) = surface[texel * 4 + c];
                encoded.at(x, row, c) = 0.5f + 0.5f * surface[texel * 4 + c];
                color.at(x, row, c) = albedo[texel * 4 + c] / 255.0f;
            }
        }
    const std::filesystem::path d(dir);
    writeImage((d / "height.exr").string(), height);
    writeImage((d / "height.png").string(), height);
    writeImage((d / "normal.exr").string(), normal);
    writeImage((d / "normal.png").string(), encoded);
    writeImage((d / "albedo.png").string(), color);
    std::printf("exported height, normal and albedo maps (%dx%d) to %s\n", w, h, dir.c_str());
}

} // namespace hfx::demo
