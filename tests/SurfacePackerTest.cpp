#include "support/Fixtures.h"

#include "hfx/compute/SurfacePacker.h"
#include "hfx/core/Error.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace hfx::test {
namespace {

class SurfacePackerTest : public ClTest {
protected:
    /// Packs `texels` (float4 each) on the device and reads the packed bytes back.
    std::vector<unsigned char> pack(const std::vector<float>& texels, SurfaceFormat format) {
        const int n = int(texels.size() / 4);
        cl::Buffer in(cl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, texels.size() * sizeof(float),
                      const_cast<float*>(texels.data()));
        SurfacePacker packer(cl(), n, 1, format);
        packer.run(in);
        std::vector<unsigned char> out(packer.bytes());
        cl().queue().enqueueReadBuffer(packer.output(), CL_TRUE, 0, out.size(), out.data());
        return out;
    }
};

/// Every kind of value a field can hold and some it must survive: normal components in
/// [-1, 1], heights in [0, 1], the rounding ties and the values past the ends.
std::vector<float> probeTexels() {
    std::vector<float> v = {0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 0.25f, 1.0f / 3.0f, 2.0f / 3.0f,
                            1e-8f, -1e-8f, 0.999999f, 1.5f, -1.5f, 65504.0f, 1e6f,
                            // 8-bit ties: (k + 0.5) / 255 heights, (2k + 1) / 255 - 1 normals
                            0.5f / 255.0f, 127.5f / 255.0f, 1.0f / 255.0f - 1.0f, 253.0f / 255.0f - 1.0f};
    for (int i = 0; i <= 200; ++i) v.push_back(std::sin(0.37f * float(i)) * (i % 2 ? 1.0f : 0.73f));
    while (v.size() % 4) v.push_back(0.0f);
    return v;
}

// IEEE binary16 of `f`, rounded to nearest even: the compiler's own conversion where it has the
// type (GCC 12, clang 15 on x86), else the same worked out in doubles (exact for every float).
std::uint16_t halfOf(float f) {
#if (defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12) || (defined(__clang__) && __clang_major__ >= 15)
    const _Float16 h = static_cast<_Float16>(f);
    std::uint16_t bits;
    std::memcpy(&bits, &h, 2);
    return bits;
#else
    const std::uint16_t sign = std::signbit(f) ? 0x8000 : 0;
    if (std::isnan(f)) return sign | 0x7e00;
    const double a = std::fabs(double(f));
    if (a >= 65520.0) return sign | 0x7c00; // half of the last step past 65504 rounds to infinity
    if (a < 0x1p-14) return sign | std::uint16_t(std::nearbyint(a * 0x1p24)); // subnormal (1024: the least normal)
    int e = 0;
    std::frexp(a, &e); // a = m 2^e, m in [0.5, 1)
    double q = std::nearbyint(std::ldexp(a, 11 - e)); // 1024..2048
    if (q == 2048.0) q = 1024.0, ++e;
    return sign | std::uint16_t((e - 1 + 15) << 10 | (int(q) - 1024));
#endif
}

TEST_F(SurfacePackerTest, HalfMatchesCppRoundToNearestEvenBitForBit) {
    const std::vector<float> texels = probeTexels();
    const std::vector<unsigned char> packed = pack(texels, SurfaceFormat::Float16);
    ASSERT_EQ(packed.size(), texels.size() * 2);
    for (size_t i = 0; i < texels.size(); ++i) {
        const std::uint16_t want = halfOf(texels[i]);
        std::uint16_t got;
        std::memcpy(&got, &packed[2 * i], 2);
        ASSERT_EQ(got, want) << "texel value " << texels[i] << " at " << i;
    }
    // Analytic anchors: 1.0 is 0x3c00, -1.0 0xbc00, 0.5 0x3800; 1e6 overflows to +inf (0x7c00).
    auto bits = [&](size_t i) { std::uint16_t b; std::memcpy(&b, &packed[2 * i], 2); return b; };
    EXPECT_EQ(bits(1), 0x3c00);
    EXPECT_EQ(bits(2), 0xbc00);
    EXPECT_EQ(bits(3), 0x3800);
    EXPECT_EQ(bits(14), 0x7c00);
}

TEST_F(SurfacePackerTest, Unorm8EncodesNormalsAndHeightsRoundedToNearest) {
    std::vector<float> texels = probeTexels();
    texels[16] = std::numeric_limits<float>::quiet_NaN(); // never fed by HFX; must still not be garbage
    const std::vector<unsigned char> packed = pack(texels, SurfaceFormat::Unorm8);
    ASSERT_EQ(packed.size(), texels.size());
    for (size_t i = 0; i < texels.size(); ++i) {
        const float t = texels[i];
        // In float, step by step, as the kernel computes it (with contraction off).
        const float e = i % 4 == 3 ? t : t * 0.5f + 0.5f;
        const int want = std::isnan(t) ? 0 : int(std::fmin(std::fmax(e, 0.0f), 1.0f) * 255.0f + 0.5f);
        ASSERT_EQ(int(packed[i]), want) << "texel value " << t << " at " << i << " (" << (i % 4 == 3 ? "height" : "normal") << ")";
    }
    // Analytic anchors: normals 0 -> 128 (0.5 * 255 rounds up), 1 -> 255, -1 -> 0; height 0.5 -> 128.
    EXPECT_EQ(packed[0], 128); // normal x = 0
    EXPECT_EQ(packed[1], 255); // normal y = 1
    EXPECT_EQ(packed[2], 0);   // normal z = -1
    EXPECT_EQ(packed[3], 128); // height 0.5
}

TEST_F(SurfacePackerTest, RefusesFloat32AndShortInput) {
    EXPECT_THROW(SurfacePacker(cl(), 8, 8, SurfaceFormat::Float32), Error);
    SurfacePacker packer(cl(), 8, 8, SurfaceFormat::Float16);
    cl::Buffer small(cl().context(), CL_MEM_READ_ONLY, 8 * 7 * sizeof(cl_float4));
    try {
        packer.run(small);
        FAIL() << "a buffer one row short was packed";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("64 float4"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace hfx::test
