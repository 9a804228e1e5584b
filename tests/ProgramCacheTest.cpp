#include "support/Fixtures.h"

#include "hfx/compute/ProgramCache.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace hfx::test {
namespace {

namespace fs = std::filesystem;

fs::path freshFolder(const std::string& name) {
    const fs::path folder = outputPath("program_cache/" + name);
    fs::remove_all(folder);
    return folder;
}

const ProgramCache::Binary kBinary = {0x7f, 'E', 'L', 'F', 0, 1, 2, 3, 250, 251};

TEST(ProgramCache, StoresAndLoadsUnderTheFullKey) {
    const ProgramCache cache(freshFolder("roundtrip"));
    EXPECT_FALSE(cache.load("key a").has_value()) << "an empty cache had an entry";
    ASSERT_TRUE(cache.store("key a", kBinary));
    bool damaged = true;
    const auto loaded = cache.load("key a", &damaged);
    ASSERT_TRUE(loaded.has_value());
    EXPECT_EQ(*loaded, kBinary);
    EXPECT_FALSE(damaged);
    EXPECT_FALSE(cache.load("key b").has_value());
}

TEST(ProgramCache, AnEntryUnderAnotherKeysNameIsNotAMatch) {
    // What a hash collision or a file copied by hand looks like: the stored key differs.
    const ProgramCache cache(freshFolder("collision"));
    ASSERT_TRUE(cache.store("key a", kBinary));
    fs::copy_file(cache.entryPath("key a"), cache.entryPath("key b"));
    bool damaged = false;
    EXPECT_FALSE(cache.load("key b", &damaged).has_value());
    EXPECT_TRUE(damaged);
}

TEST(ProgramCache, TruncatedOrFlippedEntriesAreDamagedNotLoaded) {
    const ProgramCache cache(freshFolder("damage"));
    ASSERT_TRUE(cache.store("key", kBinary));
    const fs::path entry = cache.entryPath("key");
    const auto size = fs::file_size(entry);
    for (std::uintmax_t keep : {std::uintmax_t(0), std::uintmax_t(5), size / 2, size - 1}) {
        ASSERT_TRUE(cache.store("key", kBinary));
        fs::resize_file(entry, keep);
        bool damaged = false;
        EXPECT_FALSE(cache.load("key", &damaged).has_value()) << "kept " << keep << " of " << size << " bytes";
        EXPECT_TRUE(damaged) << keep;
    }
    // One flipped byte inside the binary: the checksum catches it.
    ASSERT_TRUE(cache.store("key", kBinary));
    {
        std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(size - 8 - 2));
        f.put('\x55');
    }
    bool damaged = false;
    EXPECT_FALSE(cache.load("key", &damaged).has_value());
    EXPECT_TRUE(damaged);
}

TEST(ProgramCache, DisabledOrUnwritableCachesStoreNothingAndNeverThrow) {
    const ProgramCache off;
    EXPECT_FALSE(off.enabled());
    EXPECT_FALSE(off.store("key", kBinary));
    EXPECT_FALSE(off.load("key").has_value());

    const fs::path blocker = freshFolder("blocked");
    fs::create_directories(blocker.parent_path());
    std::ofstream(blocker) << "a file where the cache folder should be";
    const ProgramCache blocked(blocker / "kernels");
    EXPECT_FALSE(blocked.store("key", kBinary));
    EXPECT_FALSE(blocked.load("key").has_value());
    fs::remove(blocker);
}

TEST(ProgramCache, KeepsUnderItsSizeByDroppingTheLeastRecentlyUsed) {
    const ProgramCache::Binary binary(1000, 7);
    const fs::path folder = freshFolder("pruned");
    const std::uintmax_t entryBytes = [&] {
        const ProgramCache probe(freshFolder("pruned_probe"));
        probe.store("k0", binary);
        return fs::file_size(probe.entryPath("k0"));
    }();
    const ProgramCache cache(folder, 3 * entryBytes); // room for three entries
    // Modification times an hour apart, oldest first, so the order does not rest on the clock's
    // resolution. Then k0, the oldest, is loaded: that makes it the most recently used.
    const auto start = fs::file_time_type::clock::now() - std::chrono::hours(10);
    for (int k = 0; k < 3; ++k) {
        const std::string key{'k', char('0' + k)}; // (not "k" + to_string: GCC 12 warns falsely of overlap)
        ASSERT_TRUE(cache.store(key, binary));
        fs::last_write_time(cache.entryPath(key), start + std::chrono::hours(k));
    }
    ASSERT_TRUE(cache.load("k0").has_value());
    ASSERT_TRUE(cache.store("k3", binary)); // four entries: the least recently used, k1, goes
    EXPECT_FALSE(fs::exists(cache.entryPath("k1"))) << "the least recently used entry was kept";
    for (const char* kept : {"k0", "k2", "k3"}) EXPECT_TRUE(fs::exists(cache.entryPath(kept))) << kept;
    // An entry larger than the whole cache is still kept alone rather than refused.
    const ProgramCache tiny(freshFolder("pruned_tiny"), 10);
    ASSERT_TRUE(tiny.store("big", binary));
    EXPECT_TRUE(tiny.load("big").has_value());
}

TEST(ProgramCache, DefaultFolderFollowsTheEnvironment) {
    const char* saved = std::getenv("HFX_KERNEL_CACHE");
    const std::string savedValue = saved ? saved : "";
    setenv("HFX_KERNEL_CACHE", "/tmp/hfx-kernels-here", 1);
    EXPECT_EQ(ProgramCache::defaultFolder(), fs::path("/tmp/hfx-kernels-here"));
    setenv("HFX_KERNEL_CACHE", "off", 1);
    EXPECT_TRUE(ProgramCache::defaultFolder().empty());
    unsetenv("HFX_KERNEL_CACHE");
    if (std::getenv("XDG_CACHE_HOME") || std::getenv("HOME")) {
        EXPECT_EQ(ProgramCache::defaultFolder().filename(), "kernels");
    }
    if (saved) setenv("HFX_KERNEL_CACHE", savedValue.c_str(), 1);
}

// The cache inside ClContext: a second context loads what the first compiled, and the loaded
// program computes what the compiled one does.
const char* kSquares = "__kernel void squares(__global float* out, float offset) {\n"
                       "    const int i = get_global_id(0);\n"
                       "    out[i] = (float)(i * i) + offset;\n}\n";

std::vector<float> runSquares(ClContext& cl, const std::string& options = {}) {
    const cl::Program& program = cl.programFromSource("squares.cl", kSquares, options);
    cl::Kernel kernel(program, "squares");
    const size_t n = 64;
    cl::Buffer out(cl.context(), CL_MEM_WRITE_ONLY, n * sizeof(float));
    kernel.setArg(0, out);
    kernel.setArg(1, 0.5f);
    cl.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n));
    std::vector<float> values(n);
    cl.queue().enqueueReadBuffer(out, CL_TRUE, 0, n * sizeof(float), values.data());
    return values;
}

void expectSquares(const std::vector<float>& values) {
    for (size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], float(i * i) + 0.5f) << i;
}

// Skips with the reason where no OpenCL device exists.
class ProgramCacheInContext : public ClTest {};

TEST_F(ProgramCacheInContext, SecondContextLoadsWhatTheFirstCompiled) {
    const fs::path folder = freshFolder("context");
    {
        ClContext first({.log = false, .kernelCache = folder.string()});
        expectSquares(runSquares(first));
        EXPECT_EQ(first.programStats().built, 1);
        EXPECT_EQ(first.programStats().loaded, 0);
        EXPECT_EQ(first.programStats().unsaved, 0) << first.programReport();
    }
    ClContext second({.log = false, .kernelCache = folder.string()});
    expectSquares(runSquares(second));
    EXPECT_EQ(second.programStats().loaded, 1) << second.programReport();
    EXPECT_EQ(second.programStats().built, 0) << second.programReport();
    EXPECT_NE(second.programReport().find("1 from the cache"), std::string::npos) << second.programReport();

    // Other build options are another program: compiled, not loaded.
    runSquares(second, "-DUNUSED_OPTION=1");
    EXPECT_EQ(second.programStats().built, 1) << second.programReport();
}

TEST_F(ProgramCacheInContext, DamagedEntryIsRebuiltAndReplaced) {
    const fs::path folder = freshFolder("damaged");
    {
        ClContext first({.log = false, .kernelCache = folder.string()});
        runSquares(first);
    }
    for (const auto& entry : fs::directory_iterator(folder)) {
        std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << "HFXCLBN1 garbage";
    }
    {
        ClContext second({.log = false, .kernelCache = folder.string()});
        expectSquares(runSquares(second));
        EXPECT_EQ(second.programStats().rejected, 1) << second.programReport();
        EXPECT_EQ(second.programStats().built, 1) << second.programReport();
    }
    ClContext third({.log = false, .kernelCache = folder.string()});
    expectSquares(runSquares(third));
    EXPECT_EQ(third.programStats().loaded, 1) << "the rebuilt binary was not saved: " << third.programReport();
}

TEST_F(ProgramCacheInContext, OffBuildsFromSourceAndWritesNothing) {
    ClContext off({.log = false, .kernelCache = "off"});
    expectSquares(runSquares(off));
    EXPECT_EQ(off.programStats().built, 1);
    EXPECT_FALSE(off.programCache().enabled());
    EXPECT_NE(off.programReport().find("no kernel cache"), std::string::npos) << off.programReport();
}

} // namespace
} // namespace hfx::test
