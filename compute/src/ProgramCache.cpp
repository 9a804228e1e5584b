#include "hfx/compute/ProgramCache.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <system_error>
#include <unistd.h>

namespace hfx {
namespace {

constexpr char kMagic[8] = {'H', 'F', 'X', 'C', 'L', 'B', 'N', '1'};
// An entry larger than this is damage, not a program (PoCL's binaries are tens of KiB).
constexpr std::uint64_t kMaxEntryBytes = 256u << 20;

std::uint64_t fnv1a(const void* data, size_t size, std::uint64_t hash = 14695981039346656037ull) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    return hash;
}

void putU64(std::string& out, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out += char((v >> (8 * i)) & 0xff);
}

bool getU64(std::string_view& in, std::uint64_t& v) {
    if (in.size() < 8) return false;
    v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t(static_cast<unsigned char>(in[i])) << (8 * i);
    in.remove_prefix(8);
    return true;
}

} // namespace

ProgramCache::ProgramCache(std::filesystem::path folder, std::uintmax_t maxBytes)
    : folder_(std::move(folder)), maxBytes_(maxBytes) {}

std::filesystem::path ProgramCache::defaultFolder() {
    if (const char* env = std::getenv("HFX_KERNEL_CACHE"); env && *env) {
        const std::string_view v(env);
        if (v == "off" || v == "0") return {};
        return env;
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "hfx" / "kernels";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "hfx" / "kernels";
    return {};
}

std::filesystem::path ProgramCache::entryPath(const std::string& key) const {
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.clbin",
                  static_cast<unsigned long long>(fnv1a(key.data(), key.size())));
    return folder_ / name;
}

std::optional<ProgramCache::Binary> ProgramCache::load(const std::string& key, bool* damaged) const {
    if (damaged) *damaged = false;
    if (!enabled()) return std::nullopt;
    std::ifstream file(entryPath(key), std::ios::binary);
    if (!file) return std::nullopt;
    const std::string content((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    auto reject = [&]() -> std::optional<Binary> {
        if (damaged) *damaged = true;
        return std::nullopt;
    };
    std::string_view in(content);
    if (in.size() < sizeof kMagic || std::memcmp(in.data(), kMagic, sizeof kMagic) != 0) return reject();
    in.remove_prefix(sizeof kMagic);
    std::uint64_t keySize = 0, binarySize = 0, checksum = 0;
    if (!getU64(in, keySize) || keySize > in.size() || in.substr(0, keySize) != key) return reject();
    in.remove_prefix(keySize);
    if (!getU64(in, binarySize) || binarySize == 0 || binarySize > kMaxEntryBytes || binarySize > in.size())
        return reject();
    Binary binary(in.begin(), in.begin() + binarySize);
    in.remove_prefix(binarySize);
    if (!getU64(in, checksum) || !in.empty() || checksum != fnv1a(binary.data(), binary.size())) return reject();
    std::error_code ec; // marks the entry as used, for prune(); a read-only cache still loads
    std::filesystem::last_write_time(entryPath(key), std::filesystem::file_time_type::clock::now(), ec);
    return binary;
}

bool ProgramCache::store(const std::string& key, const Binary& binary) const {
    if (!enabled() || binary.empty()) return false;
    std::error_code ec;
    std::filesystem::create_directories(folder_, ec);
    if (ec) return false;
    std::string content(kMagic, sizeof kMagic);
    putU64(content, key.size());
    content += key;
    putU64(content, binary.size());
    content.append(reinterpret_cast<const char*>(binary.data()), binary.size());
    putU64(content, fnv1a(binary.data(), binary.size()));

    // A name no other process or thread uses, renamed over the entry once complete.
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path final = entryPath(key);
    std::filesystem::path temp = final;
    temp += ".tmp" + std::to_string(::getpid()) + "." + std::to_string(counter++);
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out.write(content.data(), std::streamsize(content.size()));
        out.close();
        if (!out) {
            std::filesystem::remove(temp, ec);
            return false;
        }
    }
    std::filesystem::rename(temp, final, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        return false;
    }
    prune(final);
    return true;
}

void ProgramCache::prune(const std::filesystem::path& keep) const {
    struct Entry {
        std::filesystem::path path;
        std::filesystem::file_time_type used;
        std::uintmax_t bytes;
    };
    std::vector<Entry> entries;
    std::uintmax_t total = 0;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
        const std::filesystem::path& p = it->path();
        if (p.extension() != ".clbin" || !it->is_regular_file(ec)) continue;
        std::error_code e1, e2;
        const auto bytes = it->file_size(e1);
        const auto used = it->last_write_time(e2);
        if (e1 || e2) continue;
        entries.push_back({p, used, bytes});
        total += bytes;
    }
    if (total <= maxBytes_) return;
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
    for (const Entry& e : entries) {
        if (total <= maxBytes_) break;
        if (e.path == keep) continue;
        if (std::filesystem::remove(e.path, ec)) total -= e.bytes;
    }
}

} // namespace hfx
