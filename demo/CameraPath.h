#pragma once
// A keyframed camera path (--camera-path FILE): the camera's placement at given seconds, eased
// between them, for a video that flies through a scene (the headless frames' time, or a window's
// clock). Read once; the program loops give it the time and the scene places its camera.

#include <cstddef>
#include <string>
#include <vector>

namespace hfx::demo {

struct SceneOptions;

/// One key a line: SECONDS, then NAME=VALUE for any of the camera options --camera-NAME takes:
/// azimuth, elevation, distance, target=X,Y,Z, and the water's height and pitch, in their units
/// and ranges (an azimuth may run on past 360 degrees, for turns). Every line names the same ones;
/// '#' starts a comment. Between keys each value follows a monotone cubic (Fritsch and Carlson's,
/// with Fritsch and Butland's slopes): it passes through the keys and never leaves the range of the
/// two about it, and eases in and out at the first and last key; before the first key the first
/// holds, after the last the last.
class CameraPath {
public:
    /// Throws hfx::Error naming the file, and the line and value where it is one: a file that
    /// cannot be read or holds no key, times not finite or not increasing, an unknown name, a name
    /// given twice, a value not finite or out of its option's range, or a line that names other
    /// values than the first does.
    static CameraPath load(const std::string& path);

    /// `base` with the path's values at `seconds` (the camera options SceneOptions carries).
    void apply(double seconds, SceneOptions& base) const;
    /// The names the keys give ("azimuth", "target", ...), in the order of the first line.
    const std::vector<std::string>& names() const { return names_; }
    /// The keys' times, seconds, increasing; the last is the path's duration.
    const std::vector<double>& times() const { return times_; }
    double duration() const { return times_.back(); }
    const std::string& file() const { return file_; }

private:
    static constexpr size_t kMaxChannels = 8; ///< every name once: target's three and five more
    std::string file_;
    std::vector<std::string> names_;
    std::vector<double> times_;
    /// Per key, the values in channel order: each name's (target's three) one after another.
    std::vector<std::vector<double>> keys_;
    /// Per channel, the slope at each key (the monotone cubic's).
    std::vector<std::vector<double>> slopes_;
};

} // namespace hfx::demo
