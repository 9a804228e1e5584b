#include "CameraPath.h"

#include "Scene.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace hfx::demo {

namespace {

/// A name a key may give: its option's range and how many values it takes.
struct Channel {
    const char* name;
    int count;
    double lo, hi;
    const char* unit;
};
constexpr Channel kChannels[] = {
    {"azimuth", 1, -36000.0, 36000.0, "degrees"},      // turns may run on
    {"elevation", 1, -89.0, 89.0, "degrees"},          // --camera-elevation
    {"distance", 1, 1.05, 100.0, "world units"},       // --camera-distance
    {"target", 3, -100.0, 100.0, "world units"},       // --camera-target
    {"height", 1, 1.0, 2000.0, "metres"},              // --camera-height
    {"pitch", 1, 0.0, 89.0, "degrees below the horizon"}, // --camera-pitch
};

const Channel* channelNamed(const std::string& name) {
    for (const Channel& c : kChannels)
        if (name == c.name) return &c;
    return nullptr;
}

/// The number `text` holds whole, or nothing.
bool parseNumber(const std::string& text, double& value) {
    if (text.empty()) return false;
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(value);
}

} // namespace

CameraPath CameraPath::load(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(str("camera path ", path, ": cannot be read (--camera-path)"));
    CameraPath p;
    p.file_ = path;
    std::string line;
    int number = 0, firstLine = 0;
    while (std::getline(in, line)) {
        ++number;
        const std::string where = str("camera path ", path, " line ", number, ": ");
        if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream tokens(line);
        std::string token;
        if (!(tokens >> token)) continue; // blank
        double seconds = 0.0;
        if (!parseNumber(token, seconds) || seconds < 0.0)
            throw Error(str(where, "'", token, "' is not a time (seconds, finite and at least 0)"));
        if (!p.times_.empty() && !(seconds > p.times_.back()))
            throw Error(str(where, "its time ", token, " s does not come after the line before's, ", p.times_.back(),
                            " s"));
        std::vector<std::string> names;
        std::vector<double> values;
        while (tokens >> token) {
            const auto equals = token.find('=');
            const std::string name = token.substr(0, equals);
            const Channel* c = channelNamed(name);
            if (equals == std::string::npos || !c)
                throw Error(str(where, "'", token, "' is not NAME=VALUE with a NAME of azimuth, elevation, distance, "
                                                   "target, height or pitch"));
            if (std::find(names.begin(), names.end(), name) != names.end())
                throw Error(str(where, name, " is given twice"));
            const std::string text = token.substr(equals + 1);
            std::istringstream parts(text);
            std::string part;
            int count = 0;
            while (std::getline(parts, part, ',')) {
                double v = 0.0;
                if (!parseNumber(part, v)) throw Error(str(where, name, ": '", part, "' is not a finite number"));
                if (v < c->lo || v > c->hi)
                    throw Error(str(where, name, " ", part, " is outside ", c->lo, " to ", c->hi, " ", c->unit));
                values.push_back(v);
                ++count;
            }
            if (!text.empty() && text.back() == ',') throw Error(str(where, name, ": '' is not a finite number"));
            if (count != c->count)
                throw Error(str(where, name, " takes ", c->count == 3 ? "three values, X,Y,Z" : "one value", ", got '",
                                token.substr(equals + 1), "'"));
            names.push_back(name);
        }
        if (names.empty()) throw Error(str(where, "a key needs at least one NAME=VALUE after its time"));
        if (p.times_.empty()) {
            p.names_ = names;
            firstLine = number;
        } else if (names != p.names_) {
            std::string first;
            for (const std::string& n : p.names_) first += (first.empty() ? "" : ", ") + n;
            throw Error(str(where, "names other values than line ", firstLine, " does (", first,
                            "): every key gives the same ones, in the same order"));
        }
        p.times_.push_back(seconds);
        p.keys_.push_back(values);
    }
    if (p.times_.empty()) throw Error(str("camera path ", path, ": holds no key (SECONDS NAME=VALUE ...)"));
    // The monotone cubic's slopes (Fritsch and Butland's weighted harmonic mean of the secants
    // about each inner key, 0 where they differ in sign; 0 at the ends: the path eases in and out).
    const size_t n = p.times_.size(), channels = p.keys_[0].size();
    p.slopes_.assign(channels, std::vector<double>(n, 0.0));
    for (size_t c = 0; c < channels; ++c)
        for (size_t k = 1; k + 1 < n; ++k) {
            const double h0 = p.times_[k] - p.times_[k - 1], h1 = p.times_[k + 1] - p.times_[k];
            const double d0 = (p.keys_[k][c] - p.keys_[k - 1][c]) / h0, d1 = (p.keys_[k + 1][c] - p.keys_[k][c]) / h1;
            if (d0 * d1 > 0.0) p.slopes_[c][k] = 3.0 * (h0 + h1) / ((2.0 * h1 + h0) / d0 + (h1 + 2.0 * h0) / d1);
        }
    return p;
}

void CameraPath::apply(double seconds, SceneOptions& base) const {
    const size_t n = times_.size(), channels = keys_.front().size();
    std::array<double, kMaxChannels> v{}; // (no allocation: the loops call this every frame)
    if (!(seconds > times_.front()) || n == 1) {
        std::copy(keys_.front().begin(), keys_.front().end(), v.begin());
    } else if (seconds >= times_.back()) {
        std::copy(keys_.back().begin(), keys_.back().end(), v.begin());
    } else {
        const size_t k = size_t(std::upper_bound(times_.begin(), times_.end(), seconds) - times_.begin()) - 1;
        const double h = times_[k + 1] - times_[k], s = (seconds - times_[k]) / h;
        const double s2 = s * s, s3 = s2 * s;
        for (size_t c = 0; c < channels; ++c)
            v[c] = (2.0 * s3 - 3.0 * s2 + 1.0) * keys_[k][c] + (s3 - 2.0 * s2 + s) * h * slopes_[c][k] +
                   (3.0 * s2 - 2.0 * s3) * keys_[k + 1][c] + (s3 - s2) * h * slopes_[c][k + 1];
    }
    size_t c = 0;
    for (const std::string& name : names_) {
        if (name == "azimuth") base.cameraAzimuth = float(v[c]);
        if (name == "elevation") base.cameraElevation = float(v[c]);
        if (name == "distance") base.cameraDistance = float(v[c]);
        if (name == "target") base.cameraTarget = glm::vec3(float(v[c]), float(v[c + 1]), float(v[c + 2]));
        if (name == "height") base.cameraHeight = float(v[c]);
        if (name == "pitch") base.cameraPitch = float(v[c]);
        c += size_t(channelNamed(name)->count);
    }
}

} // namespace hfx::demo
