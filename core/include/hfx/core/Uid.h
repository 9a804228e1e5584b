#pragma once
// Identities for GL-owning objects that caches key on (SurfaceTextures, Mesh): unique in the
// process, never 0, never reused. An address is none of these: a new object can take a freed
// one's, and a moved one leaves its own behind.

#include <cstdint>
#include <utility>

namespace hfx {

/// The next identity (thread-safe).
std::uint64_t nextUid();

/// An owner's identity: a move takes it along and leaves the owner moved from a new one, so no
/// two live owners share one.
class Uid {
public:
    Uid() : value_(nextUid()) {}
    Uid(Uid&& other) noexcept : value_(std::exchange(other.value_, nextUid())) {}
    Uid& operator=(Uid&& other) noexcept {
        value_ = std::exchange(other.value_, nextUid());
        return *this;
    }
    Uid(const Uid&) = delete;
    Uid& operator=(const Uid&) = delete;
    std::uint64_t value() const { return value_; }

private:
    std::uint64_t value_;
};

} // namespace hfx
