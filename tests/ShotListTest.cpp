// The shot list that drives the decal wall headless: what it reads, what it refuses (with the
// file and line), and that formatShot writes what it reads back.

#include "hfx/core/Error.h"
#include "hfx/tools/ShotList.h"

#include <gtest/gtest.h>

namespace hfx {
namespace {

std::string errorOf(std::string_view text) {
    try {
        parseShotList(text, "list.txt");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(ShotList, ReadsShotsCommentsAndBlankLines) {
    const auto shots = parseShotList("# a volley\n\nbullet 0 0.25 0.5\r\n  explosion 3 1.5 -0.25 42  # big\nclick 4 640 360");
    ASSERT_EQ(shots.size(), 3u);
    EXPECT_EQ(shots[0].kind, Shot::Kind::Bullet);
    EXPECT_EQ(shots[0].frame, 0);
    EXPECT_DOUBLE_EQ(shots[0].a, 0.25);
    EXPECT_EQ(shots[1].kind, Shot::Kind::Explosion);
    EXPECT_EQ(shots[1].seed, 42u);
    EXPECT_DOUBLE_EQ(shots[1].b, -0.25);
    EXPECT_EQ(shots[1].line, 4);
    EXPECT_EQ(shots[2].kind, Shot::Kind::Click);
    EXPECT_DOUBLE_EQ(shots[2].a, 640.0);
    EXPECT_TRUE(parseShotList("").empty());
}

TEST(ShotList, RefusesBadLinesNamingFileAndLine) {
    EXPECT_NE(errorOf("bullet 0 0.5 0.5\nrocket 1 0.5 0.5").find("list.txt:2: unknown shot 'rocket'"), std::string::npos);
    EXPECT_NE(errorOf("bullet 0 0.5").find("list.txt:1:"), std::string::npos);
    EXPECT_NE(errorOf("bullet -1 0.5 0.5").find("frame"), std::string::npos);
    EXPECT_NE(errorOf("bullet 0 nan 0.5").find("finite"), std::string::npos);
    EXPECT_NE(errorOf("bullet 0 0.5 0.5x").find("'0.5x'"), std::string::npos);
    EXPECT_NE(errorOf("bullet 0 0.5 0.5 7").find("at most"), std::string::npos);
    EXPECT_NE(errorOf("explosion 0 0.5 0.5 -7").find("seed"), std::string::npos);
    EXPECT_NE(errorOf("bullet 99999999999 0.5 0.5").find("frame"), std::string::npos);
    EXPECT_THROW(readShotList("/no/such/shots.txt"), Error);
}

TEST(ShotList, FormatReadsBack) {
    const std::vector<Shot> shots = {{Shot::Kind::Bullet, 2, 0.1, 1.0 / 3.0, 1, 0},
                                     {Shot::Kind::Explosion, 5, 1.75, 0.2, 99, 0},
                                     {Shot::Kind::Click, 9, 12.5, 700, 1, 0}};
    std::string text;
    for (const Shot& s : shots) text += formatShot(s) + "\n";
    const auto back = parseShotList(text);
    ASSERT_EQ(back.size(), shots.size());
    for (size_t i = 0; i < shots.size(); ++i) {
        EXPECT_EQ(back[i].kind, shots[i].kind);
        EXPECT_EQ(back[i].frame, shots[i].frame);
        EXPECT_EQ(back[i].a, shots[i].a);
        EXPECT_EQ(back[i].b, shots[i].b);
        if (shots[i].kind == Shot::Kind::Explosion) {
            EXPECT_EQ(back[i].seed, shots[i].seed);
        }
    }
}

} // namespace
} // namespace hfx
