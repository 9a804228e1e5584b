#include "support/Fixtures.h"

#include "hfx/compute/SurfacePacker.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/PixelBuffer.h"
#include "hfx/effects/SineWavesEffect.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace hfx::test {
namespace {

class Transfer : public DeviceTest {};

TEST_F(Transfer, PixelBufferAndMapPathsGiveTheSameTexturesInEveryFormat) {
    for (SurfaceFormat format : kSurfaceFormats) {
        SineWavesEffect mapped(cl(), {.waves = {.size = 64}, .surface = {.format = format, .transfer = TransferPath::Map}});
        SineWavesEffect pixels(cl(), {.waves = {.size = 64}, .surface = {.format = format, .transfer = TransferPath::PixelBuffer}});
        EXPECT_EQ(mapped.transferPath(), TransferPath::Map);
        EXPECT_EQ(pixels.transferPath(), TransferPath::PixelBuffer);
        for (int frame = 0; frame < 3; ++frame) {
            mapped.update(0.1);
            pixels.update(0.1);
            ASSERT_EQ(readSurface(pixels.textures()), readSurface(mapped.textures()))
                << surfaceFormatName(format) << ", sequential frame " << frame;
        }
        // Overlapped: the next field's kernels run while this one is read.
        for (int frame = 0; frame < 3; ++frame) {
            mapped.beginUpdate(0.1);
            pixels.beginUpdate(0.1);
            mapped.endUpdate();
            pixels.endUpdate();
            ASSERT_EQ(readSurface(pixels.textures()), readSurface(mapped.textures()))
                << surfaceFormatName(format) << ", overlapped frame " << frame;
        }
        // And the frames move: a path that uploaded a stale buffer would still match above.
        const std::vector<float> before = readSurface(pixels.textures());
        pixels.update(0.1);
        EXPECT_NE(readSurface(pixels.textures()), before) << surfaceFormatName(format);
    }
}

TEST_F(Transfer, AutoPicksThePixelBufferWhereTheDeviceSharesHostMemory) {
    const bool unified = cl().device().getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
    EXPECT_EQ(chooseTransferPath(cl(), TransferPath::Auto), unified ? TransferPath::PixelBuffer : TransferPath::Map);
    EXPECT_EQ(chooseTransferPath(cl(), TransferPath::Map), TransferPath::Map);
    SineWavesEffect water(cl(), {.waves = {.size = 64}});
    EXPECT_NE(water.transferPath(), TransferPath::Auto);
    EXPECT_NE(water.transferDescription().find(transferPathName(water.transferPath())), std::string::npos)
        << water.transferDescription();
    EXPECT_EQ(parseTransferPath("pixel-buffer"), TransferPath::PixelBuffer);
    EXPECT_NE(messageOf([] { parseTransferPath("dma"); }).find("known: auto, map, pixel-buffer"), std::string::npos);
}

TEST_F(Transfer, DestroyingAnEffectWithAnUpdateInFlightWaitsForIt) {
    // The kernels of an overlapped update write the pixel buffer's memory, which GL frees with
    // the effect: the destructor must wait for them. A marker enqueued behind the update's
    // kernels (in-order queue) is complete the moment the destructor returns only if it waited;
    // a 1024² step takes milliseconds, the destructor alone microseconds.
    cl::Event marker;
    {
        SineWavesEffect water(cl(), {.waves = {.size = 1024}, .surface = {.transfer = TransferPath::PixelBuffer}});
        water.beginUpdate(0.1);
        cl().queue().enqueueMarkerWithWaitList(nullptr, &marker);
    }
    EXPECT_EQ(marker.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE)
        << "the effect's memory went while its kernels still ran";
}

TEST_F(Transfer, PixelBufferUploadsWhatIsWrittenIntoItsMemory) {
    SurfaceTextures textures({.width = 4, .height = 2, .mipmaps = false, .format = SurfaceFormat::Unorm8});
    PixelBuffer pixels(4 * 2 * 4);
    auto* bytes = static_cast<unsigned char*>(pixels.memory());
    for (int frame = 0; frame < 2; ++frame) {
        pixels.waitUntilRead();
        for (int i = 0; i < 32; ++i) bytes[i] = static_cast<unsigned char>(i * 5 + frame * 50);
        pixels.uploadTexels(textures);
        const std::vector<float> read = readSurface(textures);
        for (int i = 0; i < 32; ++i)
            ASSERT_NEAR(read[i], (i * 5 + frame * 50) / 255.0, 1e-6) << "frame " << frame << " byte " << i;
    }
    GLint bound = -1;
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &bound);
    EXPECT_EQ(bound, 0) << "the upload left its buffer bound";
    // Too small a buffer for the surface: refused.
    PixelBuffer small(16);
    EXPECT_NE(messageOf([&] { small.uploadTexels(textures); }).find("needs 32 bytes"), std::string::npos);
}

} // namespace
} // namespace hfx::test
