#include "hfx/compute/DamageLog.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <locale>
#include <optional>
#include <sstream>

namespace hfx {

const char* impactKindName(ImpactKind kind) { return kind == ImpactKind::Bullet ? "bullet" : "explosion"; }

float HealCurve::at(double age) const {
    if (duration <= 0.0 || age <= start) return 1.0f;
    const double t = std::min((age - start) / duration, 1.0);
    const double s = t * t * (3.0 - 2.0 * t);
    return float(1.0 + (double(end) - 1.0) * s);
}

void HealCurve::validate(const char* channel) const {
    if (!(start >= 0.0) || !std::isfinite(start) || !(duration >= 0.0) || !std::isfinite(duration))
        throw Error(str("the ", channel, " heal curve needs start and duration >= 0 and finite, got ", start, " and ",
                        duration));
    if (!(end >= 0.0f && end <= 1.0f))
        throw Error(str("the ", channel, " heal curve's end must be in [0, 1], got ", end));
}

void DamageLook::validate() const {
    height.validate("height");
    scorch.validate("scorch");
    roughness.validate("roughness");
    occlusion.validate("occlusion");
    glow.validate("glow");
    if (!(maxStrength >= 1.0f && maxStrength <= 16.0f))
        throw Error(str("DamageLook.maxStrength must be in [1, 16], got ", maxStrength));
}

void DamageLogConfig::validate() const {
    if (budget < 1 || budget > 65536) throw Error(str("DamageLogConfig.budget must be in [1, 65536], got ", budget));
    if (!(healStep > 0.0 && healStep <= 60.0))
        throw Error(str("DamageLogConfig.healStep must be in (0, 60] seconds, got ", healStep));
    if (!(glowStep > 0.0 && glowStep <= 60.0))
        throw Error(str("DamageLogConfig.glowStep must be in (0, 60] seconds, got ", glowStep));
    if (!(mergeRadius >= 0.0f && mergeRadius <= 0.5f))
        throw Error(str("DamageLogConfig.mergeRadius must be in [0, 0.5] map widths, got ", mergeRadius));
    look.validate();
}

DamageLog::DamageLog(const DamageLogConfig& config) : config_((config.validate(), config)) {
    // Cells at least mergeRadius wide: a merge partner lies in the 3x3 cells around a point.
    grid_ = config.mergeRadius > 0.0f ? std::clamp(int(1.0f / config.mergeRadius), 1, 1024) : 1;
    slots_.resize(size_t(config.budget));
    next_.assign(size_t(config.budget), -1);
    cells_.assign(size_t(grid_) * grid_, -1);
}

int DamageLog::cellOf(float u, float v) const {
    const int x = std::min(int(u * float(grid_)), grid_ - 1), y = std::min(int(v * float(grid_)), grid_ - 1);
    return y * grid_ + x;
}

void DamageLog::link(int slot) {
    const ImpactEvent& e = slots_[size_t(slot)];
    int& first = cells_[size_t(cellOf(e.u, e.v))];
    next_[size_t(slot)] = first;
    first = slot;
}

void DamageLog::unlink(int slot) {
    const ImpactEvent& e = slots_[size_t(slot)];
    int* at = &cells_[size_t(cellOf(e.u, e.v))];
    while (*at != slot) at = &next_[size_t(*at)]; // a cell holds a few impacts: merging spaces them
    *at = next_[size_t(slot)];
}

void DamageLog::validate(const ImpactEvent& e) const {
    if (!(e.u >= 0.0f && e.u < 1.0f && e.v >= 0.0f && e.v < 1.0f))
        throw Error(str("impact at (", e.u, ", ", e.v, ") is outside the map: texcoords must lie in [0, 1)"));
    if (!std::isfinite(e.nx) || !std::isfinite(e.ny) || !std::isfinite(e.nz))
        throw Error(str("impact normal (", e.nx, ", ", e.ny, ", ", e.nz, ") is not finite"));
    if (!(e.radius > 0.0f && e.radius <= 1.0f))
        throw Error(str("impact radius must be in (0, 1] map widths, got ", e.radius));
    if (e.kind != ImpactKind::Bullet && e.kind != ImpactKind::Explosion)
        throw Error(str("impact kind ", int(e.kind), " is neither a bullet nor an explosion"));
    if (!(e.strength >= 1.0f && e.strength <= config_.look.maxStrength))
        throw Error(str("impact strength must be in [1, ", config_.look.maxStrength, "], got ", e.strength));
    if (!std::isfinite(e.time)) throw Error(str("impact time must be finite, got ", e.time));
}

namespace {
double stepped(double clock, double step) { return std::floor(clock / step) * step; }
} // namespace

double DamageLog::healTime() const { return stepped(now_, config_.healStep); }
double DamageLog::glowTime() const { return stepped(now_, config_.glowStep); }

bool DamageLog::healsBetween(double t0, double t1) const {
    const DamageLook& look = config_.look;
    for (const HealCurve* c : {&look.height, &look.scorch, &look.roughness, &look.occlusion, &look.glow}) {
        if (c->duration <= 0.0) continue;
        const double step = c == &look.glow ? config_.glowStep : config_.healStep;
        const double r0 = stepped(t0, step), r1 = stepped(t1, step);
        if (!(r1 > r0)) continue; // one step of its clock reads the same curve
        for (int i = 0; i < live_; ++i) {
            const double time = slots_[size_t((oldest_ + i) % config_.budget)].time;
            // Its curve moves while start < age < start + duration.
            if (r1 - time > c->start && r0 - time < c->start + c->duration) return true;
        }
    }
    return false;
}

void DamageLog::insert(const ImpactEvent& impact) {
    const int budget = config_.budget;
    if (live_ == budget) { // full: the oldest goes
        unlink(oldest_);
        oldest_ = (oldest_ + 1) % budget;
        --live_;
        ++evicted_;
    }
    const int slot = (oldest_ + live_) % budget;
    slots_[size_t(slot)] = impact;
    link(slot);
    ++live_;
    ++changes_;
}

bool DamageLog::add(ImpactEvent impact) { return addAt(impact, now_); }

bool DamageLog::addAt(ImpactEvent impact, double time) {
    if (!std::isfinite(time) || time > now_ || time < latest_)
        throw Error(str("DamageLog::addAt: the time ", time, " must be finite, at most the log's clock (now ", now_,
                        ") and no earlier than the last impact added (", latest_, ")"));
    impact.time = time;
    validate(impact);
    latest_ = time;
    ++added_;
    if (config_.mergeRadius > 0.0f) {
        const int cx = std::min(int(impact.u * float(grid_)), grid_ - 1);
        const int cy = std::min(int(impact.v * float(grid_)), grid_ - 1);
        auto gap = [&](float a, float b) {
            const float d = std::abs(a - b);
            return config_.wrap ? std::min(d, 1.0f - d) : d;
        };
        const float r2 = config_.mergeRadius * config_.mergeRadius;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                int x = cx + dx, y = cy + dy;
                if (config_.wrap) x = (x + grid_) % grid_, y = (y + grid_) % grid_;
                else if (x < 0 || y < 0 || x >= grid_ || y >= grid_) continue;
                for (int s = cells_[size_t(y * grid_ + x)]; s >= 0; s = next_[size_t(s)]) {
                    ImpactEvent& live = slots_[size_t(s)];
                    const float gu = gap(live.u, impact.u), gv = gap(live.v, impact.v);
                    if (live.kind != impact.kind || gu * gu + gv * gv >= r2) continue;
                    live.strength = std::min(live.strength + 1.0f, config_.look.maxStrength);
                    live.radius = std::max(live.radius, impact.radius);
                    live.time = time;
                    ++merged_;
                    ++changes_;
                    return true;
                }
            }
    }
    insert(impact);
    return false;
}

bool DamageLog::reaches(double clock) const {
    return clock >= 0.0 && std::isfinite(stepped(clock, config_.healStep)) &&
           std::isfinite(stepped(clock, config_.glowStep));
}

void DamageLog::advance(double seconds) {
    if (!(seconds >= 0.0) || !std::isfinite(seconds))
        throw Error(str("DamageLog::advance: seconds must be >= 0 and finite, got ", seconds));
    if (!reaches(now_ + seconds))
        throw Error(str("DamageLog::advance: ", seconds, " s would take the clock past any its heal curves read"));
    now_ += seconds;
}

void DamageLog::clear() {
    std::fill(cells_.begin(), cells_.end(), -1);
    live_ = 0;
    oldest_ = 0;
    ++changes_;
}

std::vector<ImpactEvent> DamageLog::events() const {
    std::vector<ImpactEvent> out;
    out.reserve(size_t(live_));
    for (int i = 0; i < live_; ++i) out.push_back(slots_[size_t((oldest_ + i) % config_.budget)]);
    return out;
}

std::vector<BulletHole> DamageLog::stamps() const {
    const DamageLook& look = config_.look;
    std::vector<BulletHole> out;
    const double healTime = this->healTime(), glowTime = this->glowTime();
    for (const ImpactEvent& e : events()) {
        const double age = healTime - e.time;
        const float height = look.height.at(age), scorch = look.scorch.at(age), rough = look.roughness.at(age),
                    occlusion = look.occlusion.at(age), glow = look.glow.at(glowTime - e.time);
        // Merged hits deepen the crater and widen it a little.
        const float deeper = 1.0f + 0.35f * (e.strength - 1.0f), wider = 1.0f + 0.2f * (e.strength - 1.0f);
        auto heal = [&](BulletHole h) {
            h.depth = std::min(h.depth * deeper, 1.0f) * height;
            h.rimHeight *= height;
            h.scorch *= scorch;
            h.roughness *= rough;
            h.occlusion *= occlusion;
            h.glow *= glow;
            return h;
        };
        if (e.kind == ImpactKind::Bullet) {
            BulletHole h = look.bullet;
            h.u = e.u, h.v = e.v;
            h.radius = std::min(e.radius * wider, 1.0f);
            h.phase = float(e.seed % 6283) * 1e-3f;
            out.push_back(heal(h));
        } else {
            Explosion x = look.explosion;
            x.u = e.u, x.v = e.v;
            x.radius = std::min(e.radius * wider, 1.0f);
            x.seed = e.seed;
            for (const BulletHole& h : DecalMap::expand(x, config_.wrap ? EdgeMode::Wrap : EdgeMode::Clamp))
                out.push_back(heal(h));
        }
    }
    return out;
}

size_t DamageLog::memoryBytes() const {
    return slots_.capacity() * sizeof(ImpactEvent) + (next_.capacity() + cells_.capacity()) * sizeof(int);
}

namespace {

// Numbers are written and read with <charconv>, which no locale touches: a log saved where the
// C locale's radix is ',' or the C++ locale groups digits reads back anywhere (a server and a
// client of a networked game need not share one).

/// x as C's "%a" writes it in the C locale ("0x1.8p+0"), every bit kept.
std::string hex(double x) {
    char buffer[64];
    char* at = buffer;
    if (std::signbit(x)) *at++ = '-';
    *at++ = '0';
    *at++ = 'x';
    const auto r = std::to_chars(at, std::end(buffer), std::fabs(x), std::chars_format::hex);
    return std::string(buffer, r.ptr);
}

std::string decimal(std::uint64_t x) {
    char buffer[24];
    const auto r = std::to_chars(std::begin(buffer), std::end(buffer), x);
    return std::string(buffer, r.ptr);
}

/// A word as hex() writes it (with or without "0x") or a decimal; false where it is neither, or
/// has more after it.
bool parseNumber(const std::string& word, double& value) {
    const char* first = word.data();
    const char* const last = word.data() + word.size();
    const bool negative = first != last && *first == '-';
    if (negative || (first != last && *first == '+')) ++first;
    auto format = std::chars_format::general;
    if (last - first > 2 && first[0] == '0' && (first[1] == 'x' || first[1] == 'X')) {
        first += 2;
        format = std::chars_format::hex;
    }
    if (first == last || *first == '-' || *first == '+') return false;
    const auto r = std::from_chars(first, last, value, format);
    if (r.ec != std::errc() || r.ptr != last) return false;
    if (negative) value = -value;
    return true;
}

} // namespace

void DamageLog::save(std::ostream& out, const std::string& name) const {
    // Version 2 counts its impacts, so that a message cut short at a line's end is refused rather
    // than read as a log with fewer impacts.
    const std::vector<ImpactEvent> live = events();
    std::string text = "hfx-damage 2\nnow " + hex(now_) + "\nimpacts " + decimal(live.size()) + "\n";
    for (const ImpactEvent& e : live)
        text += str("impact ", impactKindName(e.kind), ' ', hex(e.u), ' ', hex(e.v), ' ', hex(e.nx), ' ', hex(e.ny), ' ',
                    hex(e.nz), ' ', hex(e.radius), ' ', decimal(e.seed), ' ', hex(e.time), ' ', hex(e.strength), "\n");
    out.write(text.data(), std::streamsize(text.size()));
    out.flush();
    if (!out) throw Error(str("writing the damage log to ", name, " failed"));
}

void DamageLog::save(const std::string& path) const {
    std::ofstream file(path, std::ios::trunc | std::ios::binary);
    if (!file) throw Error(str("cannot write the damage log '", path, "'"));
    save(file, str("'", path, "'"));
}

DamageLog DamageLog::load(const std::string& path, const DamageLogConfig& config) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error(str("cannot read the damage log '", path, "'"));
    return load(file, config, path);
}

DamageLog DamageLog::load(std::istream& in, const DamageLogConfig& config, const std::string& name) {
    DamageLog log(config);
    std::string line;
    int number = 0;
    auto fail = [&](const std::string& why) { return Error(str(name, ":", number, ": ", why)); };
    auto number64 = [&](std::istringstream& words, const char* what) {
        std::string word;
        if (!(words >> word)) throw fail(str("missing ", what));
        double value = 0.0;
        if (!parseNumber(word, value) || !std::isfinite(value)) throw fail(str("bad ", what, " '", word, "'"));
        return value;
    };
    auto whole64 = [&](std::istringstream& words, const char* what) {
        std::string word;
        if (!(words >> word)) throw fail(str("missing ", what));
        std::uint64_t value = 0;
        const auto r = std::from_chars(word.data(), word.data() + word.size(), value);
        if (word.empty() || r.ec != std::errc() || r.ptr != word.data() + word.size())
            throw fail(str("bad ", what, " '", word, "' (a whole number below 2^64)"));
        return value;
    };
    bool header = false, clock = false;
    int version = 0;
    std::optional<std::uint64_t> count; // version 2's "impacts N"
    std::vector<ImpactEvent> impacts;
    std::vector<int> lines; // each impact's
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back(); // a log that passed through Windows
        if (line.empty()) continue;
        std::istringstream words(line);
        words.imbue(std::locale::classic());
        std::string word;
        words >> word;
        if (!header) {
            std::string v;
            if (word != "hfx-damage" || !(words >> v) || (v != "1" && v != "2") || (words >> word))
                throw fail("not an HFX damage log (expected 'hfx-damage 2', or 1)");
            version = v[0] - '0';
            header = true;
        } else if (word == "impacts" && version == 2 && !count) {
            if (!impacts.empty()) throw fail("the impact count comes after impacts");
            count = whole64(words, "impact count");
            if (words >> word) throw fail(str("unexpected '", word, "' after the impact count"));
        } else if (word == "now") {
            log.now_ = number64(words, "clock");
            if (!log.reaches(log.now_))
                throw fail(str("the clock ", log.now_, " is not one a log reaches (from 0 on, its heal curves' "
                               "clocks finite)"));
            clock = true;
        } else if (word == "impact") {
            ImpactEvent e;
            std::string kind;
            words >> kind;
            if (kind == "bullet") e.kind = ImpactKind::Bullet;
            else if (kind == "explosion") e.kind = ImpactKind::Explosion;
            else throw fail(str("unknown impact kind '", kind, "' (bullet or explosion)"));
            e.u = float(number64(words, "u"));
            e.v = float(number64(words, "v"));
            e.nx = float(number64(words, "normal x"));
            e.ny = float(number64(words, "normal y"));
            e.nz = float(number64(words, "normal z"));
            e.radius = float(number64(words, "radius"));
            e.seed = whole64(words, "seed");
            e.time = number64(words, "time");
            e.strength = float(number64(words, "strength"));
            if (words >> word) throw fail(str("unexpected '", word, "' after the impact"));
            try {
                log.validate(e);
            } catch (const Error& error) {
                throw fail(error.what());
            }
            impacts.push_back(e);
            lines.push_back(number);
        } else {
            throw fail(str("unknown record '", word, "'"));
        }
    }
    if (in.bad()) throw Error(str("reading the damage log ", name, " failed at line ", number + 1));
    if (!header) throw Error(str(name, ": empty, not an HFX damage log"));
    if (!clock) throw Error(str(name, ": no 'now' line (the log's clock)"));
    if (version == 2 && !count) throw Error(str(name, ": no 'impacts' line (the count of its impacts)"));
    if (count && *count != impacts.size())
        throw Error(str(name, ": ", impacts.size(), " impacts where its 'impacts' line says ", *count,
                        " (the log was cut short)"));
    if (int(impacts.size()) > config.budget)
        throw Error(str(name, ": ", impacts.size(), " impacts do not fit a budget of ", config.budget));
    // As addAt() has it: no impact is later than the clock (a merge's restarted clock included).
    for (size_t i = 0; i < impacts.size(); ++i)
        if (impacts[i].time > log.now_)
            throw Error(str(name, ":", lines[i], ": the impact's time ", impacts[i].time, " is past the log's clock ",
                            log.now_));
    for (const ImpactEvent& e : impacts) {
        log.insert(e);
        log.latest_ = std::max(log.latest_, e.time); // (a merge's restarted clock is the latest)
    }
    return log;
}

} // namespace hfx
