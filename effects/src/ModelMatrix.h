#pragma once
// Internal to hfx::effects: the check every draw and pick makes of a model matrix, and its text
// for the message. Pure CPU work.

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <string>

namespace hfx {

/// A matrix's columns, for an error that names its value.
inline std::string columnsText(const glm::mat4& m) {
    return str(text(m[0]), ", ", text(m[1]), ", ", text(m[2]), ", ", text(m[3]));
}

/// Throws hfx::Error unless the model matrix is finite and its linear part invertible (the
/// normals are turned by its inverse: a scale of 0 would make them NaN). What each draw checks
/// first, with the camera and the light, before it changes anything; pickMesh and a mesh's
/// WallImpacts too, their messages led by `caller` ("pickMesh: ").
inline void checkModel(const glm::mat4& model, const char* caller = "") {
    if (!isFinite(model))
        throw Error(str(caller, "the model matrix must be finite, got the columns ", columnsText(model)));
    if (!isFinite(glm::inverse(glm::mat3(model))))
        throw Error(str(caller, "the model matrix scales some axis to 0 (no inverse to turn the normals by), got the columns ",
                        columnsText(model)));
}

} // namespace hfx
