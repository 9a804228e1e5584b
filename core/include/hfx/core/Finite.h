#pragma once
// What the checks of values handed in share: whether a vector or a matrix is finite, and a
// vector's text for the message that names it ("(1, nan, 0)").

#include "hfx/core/Error.h"

#include <glm/fwd.hpp>

#include <cmath>
#include <string>

namespace hfx {

template <glm::length_t N, typename T, glm::qualifier Q>
bool isFinite(const glm::vec<N, T, Q>& v) {
    for (glm::length_t k = 0; k < N; ++k)
        if (!std::isfinite(v[k])) return false;
    return true;
}

template <glm::length_t C, glm::length_t R, typename T, glm::qualifier Q>
bool isFinite(const glm::mat<C, R, T, Q>& m) {
    for (glm::length_t c = 0; c < C; ++c)
        if (!isFinite(m[c])) return false;
    return true;
}

template <glm::length_t N, typename T, glm::qualifier Q>
std::string text(const glm::vec<N, T, Q>& v) {
    std::string s = "(";
    for (glm::length_t k = 0; k < N; ++k) s += str(k ? ", " : "", v[k]);
    return s + ")";
}

} // namespace hfx
