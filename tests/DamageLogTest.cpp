// The damage log a game ships: a fixed budget whose memory does not grow and which evicts the
// oldest impact first, merging of close impacts (across a wrapping edge too), heal curves that
// reach their end value at the set time, and a saved log that reads back bit for bit (and
// refuses, by file and line, what it is not).

#include "support/Fixtures.h"
#include "support/Locale.h"

#include "hfx/compute/DamageLog.h"
#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace hfx::test {
namespace {

/// The same impacts to the bit, in the same order.
bool sameEvents(const std::vector<ImpactEvent>& a, const std::vector<ImpactEvent>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i].u, &b[i].u, sizeof(float) * 6) != 0 || a[i].kind != b[i].kind ||
            a[i].seed != b[i].seed || a[i].time != b[i].time || a[i].strength != b[i].strength)
            return false;
    return true;
}

TEST(DamageLog, TenThousandImpactsIntoABudgetOf256KeepMemoryFlatAndEvictTheOldest) {
    DamageLog log({.budget = 256, .mergeRadius = 0.0f});
    const size_t memory = log.memoryBytes();
    SplitMix64 random(3);
    std::vector<ImpactEvent> all;
    for (int i = 0; i < 10000; ++i) {
        const ImpactEvent e{.u = float(random.next()), .v = float(random.next()), .seed = std::uint64_t(i)};
        EXPECT_FALSE(log.add(e));
        all.push_back(e);
        log.advance(0.01);
        ASSERT_EQ(log.memoryBytes(), memory) << "after " << i + 1 << " impacts";
    }
    EXPECT_EQ(log.size(), 256);
    EXPECT_EQ(log.evicted(), 10000u - 256u);
    const std::vector<ImpactEvent> live = log.events();
    ASSERT_EQ(live.size(), 256u);
    for (size_t i = 0; i < live.size(); ++i) // the newest 256, oldest first
        EXPECT_EQ(live[i].seed, all[10000 - 256 + i].seed) << i;
}

TEST(DamageLog, CloseImpactsOfOneKindMergeAcrossTheWrapAndDeepenUpToTheCap) {
    DamageLogConfig config{.budget = 64, .mergeRadius = 0.01f};
    config.look.maxStrength = 3.0f;
    DamageLog log(config);
    EXPECT_FALSE(log.add({.u = 0.5f, .v = 0.5f}));
    log.advance(2.0);
    EXPECT_TRUE(log.add({.u = 0.505f, .v = 0.5f, .radius = 0.02f}));
    EXPECT_FALSE(log.add({.u = 0.52f, .v = 0.5f})) << "farther than the merge radius";
    EXPECT_FALSE(log.add({.u = 0.5f, .v = 0.5f, .kind = ImpactKind::Explosion})) << "another kind";
    EXPECT_TRUE(log.add({.u = 0.501f, .v = 0.499f}));
    EXPECT_TRUE(log.add({.u = 0.5f, .v = 0.5f}));
    const std::vector<ImpactEvent> live = log.events();
    ASSERT_EQ(live.size(), 3u);
    EXPECT_EQ(live[0].strength, 3.0f) << "four hits, capped at maxStrength";
    EXPECT_EQ(live[0].radius, 0.02f) << "the larger radius";
    EXPECT_EQ(live[0].time, 2.0) << "a merge restarts its healing";
    EXPECT_EQ(live[0].u, 0.5f) << "the crater stays where it was";
    EXPECT_EQ(log.merged(), 3u);

    DamageLog wrapping(config);
    wrapping.add({.u = 0.999f, .v = 0.3f});
    EXPECT_TRUE(wrapping.add({.u = 0.003f, .v = 0.3f})) << "0.004 apart across the edge";
    config.wrap = false;
    DamageLog clamped(config);
    clamped.add({.u = 0.999f, .v = 0.3f});
    EXPECT_FALSE(clamped.add({.u = 0.003f, .v = 0.3f})) << "a wall that does not tile";
}

TEST(DamageLog, HealCurvesReachTheirEndValueAtTheSetTime) {
    const HealCurve curve{.start = 2.0, .duration = 3.0, .end = 0.25f};
    EXPECT_EQ(curve.at(0.0), 1.0f);
    EXPECT_EQ(curve.at(2.0), 1.0f);
    EXPECT_EQ(curve.at(5.0), 0.25f);
    EXPECT_EQ(curve.at(100.0), 0.25f);
    float last = 1.0f;
    for (double t = 2.0; t <= 5.0; t += 0.1) {
        EXPECT_LE(curve.at(t), last) << t;
        last = curve.at(t);
    }
    EXPECT_NEAR(curve.at(3.5), 0.625f, 1e-6f) << "half way on the smoothstep";
    EXPECT_EQ(HealCurve{}.at(1e9), 1.0f) << "no duration: permanent";

    // Through the log: every channel of a bullet at its curve's end, the others untouched.
    DamageLogConfig config;
    config.look.scorch = {.start = 1.0, .duration = 4.0, .end = 0.3f};
    config.look.roughness = {.start = 0.0, .duration = 2.0, .end = 0.0f};
    config.look.height = {.start = 3.0, .duration = 7.0, .end = 0.5f};
    DamageLog log(config);
    log.add({});
    const BulletHole b = config.look.bullet;
    EXPECT_EQ(log.stamps().at(0).glow, b.glow) << "a fresh crater is hot";
    EXPECT_GT(b.glow, 0.0f);
    log.advance(5.0);
    BulletHole h = log.stamps().at(0);
    EXPECT_EQ(h.glow, 0.0f) << "its embers cool within the glow curve's 3 s";
    EXPECT_EQ(h.scorch, b.scorch * 0.3f);
    EXPECT_EQ(h.roughness, 0.0f);
    EXPECT_EQ(h.occlusion, b.occlusion);
    EXPECT_GT(h.depth, 0.5f * b.depth) << "height heals until 10 s";
    log.advance(5.0);
    h = log.stamps().at(0);
    EXPECT_EQ(h.depth, b.depth * 0.5f);
    EXPECT_EQ(h.rimHeight, b.rimHeight * 0.5f);

    // The curves move between ages 0 and 10 s (roughness from 0, height until 10): the heal clock
    // tells when the maps change.
    EXPECT_TRUE(log.healsBetween(0.0, 0.125));
    EXPECT_TRUE(log.healsBetween(9.9, 10.1));
    EXPECT_FALSE(log.healsBetween(10.0, 50.0)) << "every curve has ended";
    EXPECT_FALSE(log.healsBetween(3.0, 3.0)) << "the same heal time";
    log.advance(0.3);
    EXPECT_EQ(log.healTime(), 10.25) << "the clock rounded down to healStep = 0.125";
    EXPECT_NE(messageOf([] { DamageLog({.healStep = 0.0}); }).find("healStep"), std::string::npos);
    EXPECT_NE(messageOf([] { DamageLog({.glowStep = -1.0}); }).find("glowStep"), std::string::npos);
}

// A crater's embers cool over 3 s: read on the heal clock (8 steps a second) a 60 Hz game drew
// them dimming in jumps, a quarter of their light at once half way. On their own clock they
// change every frame by a few percent, while the slower curves keep the heal clock's steps.
TEST(DamageLog, EmbersCoolFrameByFrame) {
    DamageLogConfig config;
    config.look.scorch = {.start = 0.0, .duration = 6.0, .end = 0.0f};
    DamageLog log(config);
    log.add({});
    const BulletHole b = config.look.bullet;
    auto light = [](const BulletHole& h) { return h.glow * h.glow; }; // the lit model's emission: heat^2
    float lastLight = light(log.stamps().at(0)), worst = 0.0f;
    int glowChanges = 0, scorchChanges = 0;
    float lastScorch = log.stamps().at(0).scorch;
    const double frame = 1.0 / 60.0;
    for (int i = 1; i <= 186; ++i) { // 3.1 s of frames
        const double before = log.now();
        log.advance(frame);
        const BulletHole h = log.stamps().at(0);
        EXPECT_EQ(log.healsBetween(before, log.now()), light(h) != lastLight || h.scorch != lastScorch) << i;
        if (lastLight > 0.05f * light(b)) worst = std::max(worst, (lastLight - light(h)) / lastLight);
        glowChanges += light(h) != lastLight;
        scorchChanges += h.scorch != lastScorch;
        lastLight = light(h);
        lastScorch = h.scorch;
    }
    EXPECT_EQ(lastLight, 0.0f) << "cold after the glow curve's 3 s";
    EXPECT_GE(glowChanges, 170) << "a change nearly every frame";
    EXPECT_LT(worst, 0.1f) << "no frame drops a tenth of the light while it glows brightly enough to see";
    EXPECT_EQ(scorchChanges, 24) << "the soot on the heal clock: 8 steps a second, 0.125 to 3 s";
}

TEST(DamageLog, ExplosionsExpandIntoTheirDebrisWithTheirSeed) {
    DamageLog log;
    log.add({.u = 0.3f, .v = 0.6f, .radius = 0.05f, .kind = ImpactKind::Explosion, .seed = 77});
    const std::vector<BulletHole> stamps = log.stamps();
    Explosion x = DamageLogConfig{}.look.explosion;
    x.u = 0.3f, x.v = 0.6f, x.radius = 0.05f, x.seed = 77;
    const std::vector<BulletHole> expected = DecalMap::expand(x, EdgeMode::Wrap);
    ASSERT_EQ(stamps.size(), expected.size());
    for (size_t i = 0; i < stamps.size(); ++i) {
        EXPECT_EQ(stamps[i].u, expected[i].u);
        EXPECT_EQ(stamps[i].scorch, expected[i].scorch);
    }
}

TEST(DamageLog, ASavedLogReadsBackBitForBit) {
    DamageLog log({.budget = 100, .mergeRadius = 0.02f});
    SplitMix64 random(9);
    for (int i = 0; i < 400; ++i) {
        log.add({.u = float(random.next()), .v = float(random.next()), .nx = float(random.uniform(-1, 1)),
                 .ny = 0.25f, .nz = 0.96875f, .radius = float(random.uniform(0.001, 0.05)),
                 .kind = i % 7 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet, .seed = random.nextBits()});
        log.advance(random.uniform(0.0, 0.1));
    }
    ASSERT_GT(log.merged(), 0u);
    const std::string path = outputPath("damage.log");
    log.save(path);
    const DamageLog back = DamageLog::load(path, {.budget = 100, .mergeRadius = 0.02f});
    EXPECT_EQ(back.now(), log.now());
    EXPECT_TRUE(sameEvents(log.events(), back.events()));
    const auto sa = log.stamps(), sb = back.stamps();
    ASSERT_EQ(sa.size(), sb.size());
    EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(BulletHole)), 0);
    EXPECT_NE(messageOf([&] { DamageLog::load(path, {.budget = 10}); }).find("budget of 10"), std::string::npos);
}

TEST(DamageLog, ALogSavedIntoAStreamUnderAnyLocaleIsTheFilesTextAndReadsBackBitForBit) {
    // A server's snapshot for a client joining late goes through a string stream; the server and
    // the client may run under different locales. With the program's C++ locale grouping digits
    // and writing ',' for the decimal point (as std::locale::global(std::locale("")) gives on a
    // German desktop), the text is the classic locale's to the byte (the seeds, 64-bit, are where
    // grouping would show) and reads back into the same impacts.
    DamageLog log({.budget = 64, .mergeRadius = 0.0f});
    SplitMix64 random(17);
    for (int i = 0; i < 40; ++i) {
        log.add({.u = float(random.next()), .v = float(random.next()), .nx = -0.25f, .ny = 0.0f, .nz = 0.96875f,
                 .radius = float(random.uniform(0.001, 0.05)),
                 .kind = i % 5 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet, .seed = random.nextBits()});
        log.advance(random.uniform(0.0, 0.3));
    }
    const std::string path = outputPath("damage-classic.log");
    log.save(path);
    std::ifstream file(path, std::ios::binary);
    const std::string classic{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    ASSERT_NE(classic.find("impact explosion"), std::string::npos);

    std::string german;
    DamageLog back({.budget = 64});
    std::string refusal;
    {
        const GermanLocale locale;
        std::ostringstream out; // takes the global locale
        log.save(out, "the server's snapshot");
        german = out.str();
        std::istringstream in(german);
        back = DamageLog::load(in, {.budget = 64, .mergeRadius = 0.0f}, "the server's snapshot");
        std::istringstream bad("hfx-damage 1\nnow 0x1p+0\nimpact bullet 0,5 0.5 0 0 1 0.1 1 0 1\n");
        refusal = messageOf([&] { DamageLog::load(bad, {}, "the server's snapshot"); });
        std::ostringstream grouped; // the test can tell: this locale groups a seed's digits
        grouped << std::uint64_t(1234567);
        ASSERT_EQ(grouped.str(), "1.234.567");
        // And the messages HFX builds (and its kernels' options) read as anywhere else.
        EXPECT_EQ(str(1234567, ' ', 0.5), "1234567 0.5");
    }
    EXPECT_EQ(german, classic);
    EXPECT_EQ(refusal, "the server's snapshot:3: bad u '0,5'");
    EXPECT_EQ(back.now(), log.now());
    EXPECT_TRUE(sameEvents(log.events(), back.events()));
    // Files from Windows (CRLF lines) and decimals written by hand read too.
    std::istringstream windows("hfx-damage 1\r\nnow 2.5\r\nimpact bullet 0.5 0.25 0 0 1 0.01 7 1.5 1\r\n");
    const DamageLog hand = DamageLog::load(windows, {}, "a hand-written log");
    EXPECT_EQ(hand.now(), 2.5);
    ASSERT_EQ(hand.size(), 1);
    EXPECT_EQ(hand.events()[0].v, 0.25f);
    EXPECT_EQ(hand.events()[0].seed, 7u);
}

TEST(DamageLog, AClientAddingTheServersImpactsLateWithTheirTimesHoldsTheSameDamage) {
    // A server logs impacts as they come (merges and evictions among them); a client receives
    // each with its time, late, and adds it at that time: its impacts and stamps are the
    // server's, to the bit, at any clock after. Added at its own clock instead (add()), they heal
    // from the wrong time and the stamps differ.
    const DamageLogConfig config{.budget = 64, .mergeRadius = 0.03f};
    DamageLog server(config), client(config), careless(config);
    SplitMix64 random(21);
    struct Sent {
        ImpactEvent impact;
        double time;
    };
    std::vector<Sent> sent;
    for (int i = 0; i < 300; ++i) {
        const ImpactEvent e{.u = float(random.next()), .v = float(random.next()), .radius = float(random.uniform(0.005, 0.03)),
                            .kind = i % 9 == 0 ? ImpactKind::Explosion : ImpactKind::Bullet, .seed = random.nextBits()};
        server.add(e);
        sent.push_back({e, server.now()});
        server.advance(random.uniform(0.0, 0.5));
        // The client hears of them in bursts, a little later, and keeps its clock with the server's.
        if (i % 10 == 9) {
            client.advance(server.now() - client.now());
            careless.advance(server.now() - careless.now());
            for (const Sent& s : sent) {
                client.addAt(s.impact, s.time);
                careless.add(s.impact);
            }
            sent.clear();
        }
    }
    ASSERT_GT(server.merged(), 0u);
    ASSERT_GT(server.evicted(), 0u);
    ASSERT_EQ(client.now(), server.now());
    EXPECT_TRUE(sameEvents(server.events(), client.events()));
    // (By 200 s every heal curve has reached its end: the careless client catches up there.)
    for (const double later : {0.0, 30.0, 200.0}) {
        server.advance(later);
        client.advance(later);
        careless.advance(later);
        const auto sa = server.stamps(), sb = client.stamps(), sc = careless.stamps();
        ASSERT_EQ(sa.size(), sb.size());
        EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(BulletHole)), 0) << "after " << later << " s more";
        if (later < 100.0) {
            EXPECT_TRUE(sa.size() != sc.size() || std::memcmp(sa.data(), sc.data(), sa.size() * sizeof(BulletHole)) != 0)
                << "the client's own clock gave the server's stamps: the test cannot tell";
        }
    }
    // A time after the clock, one before the last impact's, or not a number is refused by name
    // and changes nothing.
    const std::vector<ImpactEvent> before = client.events();
    const ImpactEvent e{.u = 0.5f, .v = 0.5f};
    EXPECT_NE(messageOf([&] { client.addAt(e, client.now() + 1.0); }).find("at most the log's clock"), std::string::npos);
    EXPECT_NE(messageOf([&] { client.addAt(e, 0.0); }).find("no earlier than the last impact added"), std::string::npos);
    EXPECT_NE(messageOf([&] { client.addAt(e, std::nan("")); }).find("DamageLog::addAt: the time nan"), std::string::npos);
    EXPECT_TRUE(sameEvents(before, client.events()));
}

TEST(DamageLog, BadImpactsAndBadFilesAreRefusedByNameAndChangeNothing) {
    DamageLog log;
    log.add({.u = 0.5f, .v = 0.5f});
    EXPECT_NE(messageOf([&] { log.add({.u = 1.0f}); }).find("outside the map"), std::string::npos);
    EXPECT_NE(messageOf([&] { log.add({.nx = std::nanf("")}); }).find("normal"), std::string::npos);
    EXPECT_NE(messageOf([&] { log.add({.radius = 0.0f}); }).find("radius"), std::string::npos);
    EXPECT_NE(messageOf([&] { log.add({.kind = ImpactKind(9)}); }).find("kind"), std::string::npos);
    EXPECT_NE(messageOf([&] { log.advance(-1.0); }).find("seconds"), std::string::npos);
    EXPECT_EQ(log.size(), 1);
    EXPECT_EQ(log.added(), 1u);
    EXPECT_NE(messageOf([&] { DamageLog({.budget = 0}); }).find("budget"), std::string::npos);
    EXPECT_NE(messageOf([&] { DamageLog({.mergeRadius = -1.0f}); }).find("mergeRadius"), std::string::npos);
    DamageLogConfig badCurve;
    badCurve.look.scorch.end = 2.0f;
    EXPECT_NE(messageOf([&] { DamageLog{badCurve}; }).find("scorch heal curve"), std::string::npos);

    auto loadText = [](const std::string& text) {
        const std::string path = outputPath("bad-damage.log");
        std::ofstream(path) << text;
        return messageOf([&] { DamageLog::load(path); });
    };
    EXPECT_NE(loadText("").find("empty"), std::string::npos);
    EXPECT_NE(loadText("hello 1\n").find(":1: not an HFX damage log"), std::string::npos);
    EXPECT_NE(loadText("hfx-damage 1\nnow 0x1p+0\nimpact laser 0 0 0 0 1 0.1 1 0 1\n").find(":3: unknown impact kind 'laser'"),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 1\nnow 0\nimpact bullet 0.5 0.5 0 0 1 0.1 1 0\n").find(":3: missing strength"),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 1\nnow 0\nimpact bullet 1.5 0.5 0 0 1 0.1 1 0 1\n").find(":3: impact at (1.5"),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 1\nimpact bullet 0.5 0.5 0 0 1 0.1 1 0 1\n").find("no 'now' line"),
              std::string::npos);
    // Version 2 counts its impacts: a log cut short at a line's end is refused.
    EXPECT_NE(loadText("hfx-damage 2\nnow 0\nimpact bullet 0.5 0.5 0 0 1 0.1 1 0 1\n").find("no 'impacts' line"),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 2\nnow 0\nimpacts 2\nimpact bullet 0.5 0.5 0 0 1 0.1 1 0 1\n")
                  .find("1 impacts where its 'impacts' line says 2 (the log was cut short)"),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 2\nnow 0\nimpacts two\n").find(":3: bad impact count 'two'"), std::string::npos);
    EXPECT_NE(loadText("hfx-damage 2\nnow 0\nimpacts 99999999999999999999\n").find(":3: bad impact count"),
              std::string::npos); // past 2^64: not read as 0
    EXPECT_NE(loadText("hfx-damage 3\nnow 0\n").find(":1: not an HFX damage log"), std::string::npos);
    // A clock no log reaches (a peer's message is not trusted): below 0, or so far on that the heal
    // curves' clocks (now over the step) are infinite, which fed NaN ages to the stamps (the fuzz
    // target's check, tests/fuzz/FuzzDamageLog.cpp, fails on it); and an impact later than the
    // clock, which addAt() refuses.
    EXPECT_NE(loadText("hfx-damage 2\nnow -0x1p+0\nimpacts 0\n").find(":2: the clock -1 is not one a log reaches"),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 2\nnow 0x1.fffffffffffffp+1023\nimpacts 0\n").find(":2: the clock "),
              std::string::npos);
    EXPECT_NE(loadText("hfx-damage 2\nnow 0x1p+3\nimpacts 1\nimpact bullet 0.5 0.5 0 0 1 0.1 1 0x1p+4 1\n")
                  .find(":4: the impact's time 16 is past the log's clock 8"),
              std::string::npos);
    DamageLog running;
    running.advance(1e300);
    EXPECT_NE(messageOf([&] { running.advance(1.7e308); }).find("past any its heal curves read"), std::string::npos);
    EXPECT_EQ(running.now(), 1e300);
    EXPECT_TRUE(std::isfinite(running.healTime()));
    EXPECT_NE(messageOf([] { DamageLog::load("/no/such/damage.log"); }).find("/no/such/damage.log"), std::string::npos);
}

} // namespace
} // namespace hfx::test
