// ValidateSupport.h: what Scene::validate()'s parts share: object paths, finiteness and the
// InvalidInput error; and the checks of materials, textures, lights and cameras
// (ValidateAppearance.cpp).
#pragma once

#include <lantern/Scene.h>

#include <cmath>
#include <string>

namespace lantern::validation {

inline std::string at(const char* array, std::size_t i) {
    return std::string(array) + "[" + std::to_string(i) + "]";
}

inline bool finite(double v) { return std::isfinite(v); }
inline bool finite(const glm::dvec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }
inline bool finite(const glm::dvec4& v) { return finite(glm::dvec3(v)) && finite(v.w); }
inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline Error invalid(const std::string& object, const std::string& message) {
    return makeError(ErrorCode::InvalidInput, message, object);
}

/// Materials (sides, maps), textures, lights and cameras.
Result<void> validateAppearance(const Scene& scene);

} // namespace lantern::validation
