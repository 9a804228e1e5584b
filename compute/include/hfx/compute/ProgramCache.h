#pragma once
// A folder of OpenCL program binaries, so that a second start of an application creates its
// programs from binaries instead of compiling OpenCL C again. Drivers differ: PoCL keeps its own
// kernel cache but still runs Clang over the source to find it; many GPU drivers keep none.
//
// An entry is keyed by everything the binary depends on — platform, device and driver names and
// versions, build options and the source after includes — and stores that key in full, so a
// stale or colliding entry is never mistaken for a match. Entries are written to a temporary
// file and renamed into place, so concurrent processes never see half an entry.
// A cache never throws: an unreadable folder or entry is a miss, an unwritable one a lost save.
// It stays under a size: after a save, the least recently used entries (by modification time,
// which a load refreshes) go until the rest fit — every edit of a kernel makes a new entry.
//
// Thread: one ProgramCache per ClContext; two processes may share a folder.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace hfx {

class ProgramCache {
public:
    using Binary = std::vector<unsigned char>;

    static constexpr std::uintmax_t kDefaultMaxBytes = 64u << 20;

    /// A cache in `folder`, created on the first save; an empty folder is a disabled cache.
    /// maxBytes: the entries' total size it keeps after a save (at least the newest entry).
    explicit ProgramCache(std::filesystem::path folder = {}, std::uintmax_t maxBytes = kDefaultMaxBytes);

    /// The folder named by HFX_KERNEL_CACHE, else $XDG_CACHE_HOME/hfx/kernels, else
    /// $HOME/.cache/hfx/kernels; empty (no cache) when HFX_KERNEL_CACHE is "off" or "0" or no
    /// home is known.
    static std::filesystem::path defaultFolder();

    bool enabled() const { return !folder_.empty(); }
    const std::filesystem::path& folder() const { return folder_; }

    /// The binary stored under `key`, or nothing when there is none or the entry is damaged or
    /// belongs to another key (`damaged` is then set). A hit marks the entry as just used.
    std::optional<Binary> load(const std::string& key, bool* damaged = nullptr) const;
    /// Stores `binary` under `key`; false when the folder or file cannot be written.
    bool store(const std::string& key, const Binary& binary) const;
    /// The entry's file for `key` (whether or not it exists).
    std::filesystem::path entryPath(const std::string& key) const;

private:
    void prune(const std::filesystem::path& keep) const;
    std::filesystem::path folder_;
    std::uintmax_t maxBytes_;
};

} // namespace hfx
