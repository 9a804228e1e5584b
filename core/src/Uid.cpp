#include "hfx/core/Uid.h"

#include <atomic>

namespace hfx {

std::uint64_t nextUid() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

} // namespace hfx
