#pragma once
// Damage as a log of impacts, for a game to ship: a fixed budget of live impacts in a ring (O(1)
// insertion, the oldest evicted first, no allocation after construction), impacts of one kind
// closer than mergeRadius merged into the one already there (a burst at one spot deepens one
// crater instead of flushing the rest of the wall out of the budget), and heal-over-time curves
// per channel (height, scorch, roughness, occlusion). The maps are a function of the live
// impacts and the clock alone: DecalMap::rebuild() of stamps() every frame, so saving the log
// (save/load: every value as a hexadecimal float) and replaying it gives the same maps bit for
// bit, for save games and for clients joining a networked game late; a client that hears of
// each impact late adds it at its time (addAt) and keeps the server's maps.
//
// Positions are texcoords in [0,1) of the damaged map; radii are in map widths.
// Thread: any (plain CPU data); one thread at a time per log.

#include "hfx/compute/DecalMap.h"

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

namespace hfx {

enum class ImpactKind : std::uint8_t { Bullet, Explosion };
const char* impactKindName(ImpactKind kind);

/// One impact as the log keeps it.
struct ImpactEvent {
    float u = 0.5f, v = 0.5f;           ///< where it hit, texcoords in [0,1)
    float nx = 0.0f, ny = 0.0f, nz = 1.0f; ///< the surface's normal there (world space; for effects and peers)
    float radius = 0.012f;              ///< its crater, map widths
    ImpactKind kind = ImpactKind::Bullet;
    std::uint64_t seed = 1;             ///< debris and the scorch's outline
    double time = 0.0;                  ///< seconds on the log's clock (DamageLog::now)
    float strength = 1.0f;              ///< impacts merged into it, each adding 1 (capped)
};

/// How one channel heals: its full value until `start` seconds after the impact, then a
/// smoothstep to `end` (a fraction of it) over `duration` seconds, reached exactly at
/// start + duration and kept. duration 0: it never changes.
struct HealCurve {
    double start = 0.0;
    double duration = 0.0;
    float end = 1.0f;
    float at(double age) const;
    void validate(const char* channel) const; ///< throws hfx::Error naming the channel
};

/// The look of impacts and how it heals, per channel.
struct DamageLook {
    BulletHole bullet{.radius = 0.012f, .depth = 0.5f, .rimHeight = 0.08f, .scorch = 0.55f, .roughness = 0.8f,
                      .occlusion = 0.6f, .scorchReach = 2.2f, .glow = 0.4f};
    Explosion explosion{.radius = 0.05f, .depth = 0.6f, .debris = 40, .scorch = 0.9f, .roughness = 0.9f,
                        .occlusion = 0.7f, .scorchReach = 2.6f, .glow = 0.8f};
    HealCurve height;                                       ///< permanent unless told
    HealCurve scorch{.start = 20.0, .duration = 60.0, .end = 0.35f}; ///< soot weathers to a stain
    HealCurve roughness{.start = 5.0, .duration = 30.0, .end = 0.4f}; ///< fresh fracture dulls
    HealCurve occlusion;
    HealCurve glow{.start = 0.0, .duration = 3.0, .end = 0.0}; ///< a fresh crater's embers cool
    float maxStrength = 3.0f; ///< merged impacts deepen and widen up to this many times the first
    void validate() const;
};

struct DamageLogConfig {
    int budget = 256;           ///< live impacts, 1 to 65536: memory is fixed by it
    float mergeRadius = 0.006f; ///< map widths; impacts of one kind closer merge; 0: never
    bool wrap = true;           ///< distances across the map's edges (a tiling wall)
    /// Heal curves are read on the clock rounded down to this many seconds (healTime()), so
    /// healing changes the maps at most 1 / healStep times a second and the maps are a function
    /// of the impacts and that clock alone.
    double healStep = 0.125;
    /// The glow curve's own step (glowTime()): embers cool in seconds, and read at healStep
    /// they dimmed in jumps of up to a quarter of their light, 8 a second. The maps change at most
    /// 1 / glowStep times a second while a crater glows.
    double glowStep = 1.0 / 60.0;
    DamageLook look;
    void validate() const;
};

class DamageLog {
public:
    explicit DamageLog(const DamageLogConfig& config = {});

    /// Adds an impact at the log's clock (its `time` is set to now()). O(1): a live impact of
    /// the same kind within mergeRadius takes it in (strength + 1 up to maxStrength, radius the
    /// larger, clock restarted: it heals from now); otherwise it takes the next slot, evicting the
    /// oldest impact when the budget is full. Throws hfx::Error and changes nothing on a position
    /// outside [0,1), a non-finite normal or a non-positive radius. Returns true when it merged.
    bool add(ImpactEvent impact);
    /// Adds an impact made at `time` on the log's clock: a peer's, received late (a server's
    /// impact on a client). As add() at that time: a merge restarts the live impact's clock at
    /// `time`. `time` must be finite, at most now() and no earlier than the last impact added:
    /// peers add in one order. A log that adds another's impacts with their times, in its order,
    /// holds the same impacts and stamps to the bit (network sync of damage). Throws hfx::Error
    /// naming the time and changes nothing otherwise, or on a bad impact as add() does.
    bool addAt(ImpactEvent impact, double time);
    /// Moves the clock on (seconds, >= 0 and finite; throws hfx::Error where the clock would pass
    /// any its heal curves read, about 1e307 s).
    void advance(double seconds);
    double now() const { return now_; }
    /// The clock the heal curves read: now() rounded down to a multiple of healStep.
    double healTime() const;
    /// The clock the glow curve reads: now() rounded down to a multiple of glowStep.
    double glowTime() const;
    /// Counts every change to the live impacts (adds, merges, clears, loads).
    std::uint64_t changes() const { return changes_; }
    /// Whether some live impact's heal curves move between the clocks t0 and t1, each curve read
    /// on its own clock (glow on glowTime()'s steps, the rest on healTime()'s): when not, and
    /// changes() has not moved, stamps() are what they were at t0.
    bool healsBetween(double t0, double t1) const;
    /// Forgets every impact (the clock keeps running).
    void clear();

    int size() const { return live_; }
    int budget() const { return config_.budget; }
    std::uint64_t added() const { return added_; }     ///< impacts given to add()
    std::uint64_t merged() const { return merged_; }   ///< of those, merged into a live one
    std::uint64_t evicted() const { return evicted_; } ///< live impacts pushed out by the budget
    /// The live impacts, oldest first.
    std::vector<ImpactEvent> events() const;
    /// The stamps of the live impacts at healTime() (their glow at glowTime()), oldest first
    /// (explosions expanded into their debris), each channel scaled by its heal curve at the
    /// impact's age: what DecalMap rebuilds.
    std::vector<BulletHole> stamps() const;
    /// The bytes the log holds, fixed at construction (the budget's slots and the merge grid).
    size_t memoryBytes() const;

    /// Writes the clock, the count of the live impacts and the impacts (text, one per line, every
    /// float in hexadecimal so it reads back exactly, whatever the C or C++ locale; version 2:
    /// version 1, without the count, still reads). Throws hfx::Error naming the file when it
    /// cannot be written.
    void save(const std::string& path) const;
    /// The same text into a stream: a string stream for a message to a client joining late, a
    /// save game's own file. `name` says what the stream is in an error.
    void save(std::ostream& out, const std::string& name = "a stream") const;
    /// Reads what save() wrote into a log of `config` (its budget must hold the saved impacts).
    /// Throws hfx::Error naming the file and line for anything else, and where fewer impacts
    /// follow than the count says (a log cut short), the clock is one no log reaches (below 0, or
    /// so large that its heal curves read it as infinite) or an impact's time is past it.
    static DamageLog load(const std::string& path, const DamageLogConfig& config = {});
    /// The same from a stream, its errors naming `name` and the line.
    static DamageLog load(std::istream& in, const DamageLogConfig& config = {}, const std::string& name = "a stream");

private:
    int cellOf(float u, float v) const;
    void link(int slot);
    void unlink(int slot);
    void validate(const ImpactEvent& impact) const;
    /// Whether the clock can stand at `clock`: from 0 on, where its heal curves' clocks are finite.
    bool reaches(double clock) const;
    /// Takes the next slot for `impact` as it is (no merging): add() and load().
    void insert(const ImpactEvent& impact);

    DamageLogConfig config_;
    std::vector<ImpactEvent> slots_; ///< the ring, `budget` slots
    std::vector<int> next_;          ///< per slot: the next slot in its grid cell, -1 at the end
    std::vector<int> cells_;         ///< per merge-grid cell: its first slot, -1 when empty
    int grid_ = 1;                   ///< merge-grid cells per edge
    int oldest_ = 0;                 ///< the oldest live slot; the next free one is oldest_ + live_
    int live_ = 0;
    double now_ = 0.0;
    double latest_ = -std::numeric_limits<double>::infinity(); ///< the time of the impact added last
    std::uint64_t added_ = 0, merged_ = 0, evicted_ = 0, changes_ = 0;
};

} // namespace hfx
