#include "hfx/tools/ShotList.h"

#include "hfx/core/Error.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace hfx {
namespace {

constexpr size_t kMaxShots = 1000000;

std::vector<std::string_view> fields(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

template <typename T>
bool parseNumber(std::string_view text, T& value) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

} // namespace

std::vector<Shot> parseShotList(std::string_view text, const std::string& name) {
    std::vector<Shot> shots;
    int lineNumber = 0;
    size_t pos = 0;
    while (pos <= text.size()) {
        const size_t eol = std::min(text.find('\n', pos), text.size());
        std::string_view line = text.substr(pos, eol - pos);
        pos = eol + 1;
        ++lineNumber;
        if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        const auto f = fields(line);
        if (f.empty()) {
            if (eol == text.size()) break;
            continue;
        }
        auto fail = [&](const std::string& what) -> Error {
            return Error(str(name, ":", lineNumber, ": ", what));
        };
        Shot shot;
        shot.line = lineNumber;
        if (f[0] == "bullet") shot.kind = Shot::Kind::Bullet;
        else if (f[0] == "explosion") shot.kind = Shot::Kind::Explosion;
        else if (f[0] == "click") shot.kind = Shot::Kind::Click;
        else throw fail(str("unknown shot '", f[0], "' (expected bullet, explosion or click)"));
        const size_t maxFields = shot.kind == Shot::Kind::Explosion ? 5 : 4;
        if (f.size() < 4) throw fail(str("'", f[0], "' needs FRAME and two coordinates, got ", f.size() - 1, " fields"));
        if (f.size() > maxFields) throw fail(str("'", f[0], "' takes at most ", maxFields - 1, " fields, got ", f.size() - 1));
        if (!parseNumber(f[1], shot.frame) || shot.frame < 0)
            throw fail(str("frame must be a whole number >= 0, got '", f[1], "'"));
        if (!parseNumber(f[2], shot.a) || !std::isfinite(shot.a))
            throw fail(str("first coordinate must be a finite number, got '", f[2], "'"));
        if (!parseNumber(f[3], shot.b) || !std::isfinite(shot.b))
            throw fail(str("second coordinate must be a finite number, got '", f[3], "'"));
        if (f.size() == 5 && !parseNumber(f[4], shot.seed))
            throw fail(str("seed must be a whole number >= 0, got '", f[4], "'"));
        if (shots.size() >= kMaxShots) throw fail(str("more than ", kMaxShots, " shots"));
        shots.push_back(shot);
        if (eol == text.size()) break;
    }
    return shots;
}

std::vector<Shot> readShotList(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(str("cannot open shot list '", path, "'"));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error(str("cannot read shot list '", path, "'"));
    return parseShotList(text.str(), path);
}

std::string formatShot(const Shot& shot) {
    char buffer[160];
    const char* kind = shot.kind == Shot::Kind::Bullet ? "bullet" : shot.kind == Shot::Kind::Explosion ? "explosion" : "click";
    if (shot.kind == Shot::Kind::Explosion)
        std::snprintf(buffer, sizeof buffer, "%s %d %.17g %.17g %llu", kind, shot.frame, shot.a, shot.b,
                      static_cast<unsigned long long>(shot.seed));
    else
        std::snprintf(buffer, sizeof buffer, "%s %d %.17g %.17g", kind, shot.frame, shot.a, shot.b);
    return buffer;
}

} // namespace hfx
