// GltfSchema.h: the JSON pass's number checks, by each property's place in the glTF schema
// (and in the extensions Lantern reads), never by its name alone: `target` is an integer in a
// buffer view and three numbers in LANTERN_camera's lookAt.
#pragma once

#include "io/gltf/GltfInternal.h"

#include <nlohmann/json.hpp>

namespace lantern::gltf {

/// What the schema says a number at some place is.
enum class NumberKind {
    Any,   ///< finite, at most 1e30 in magnitude (colours, transforms, camera parameters)
    Index, ///< an integer in 0..2^31-1 (tinygltf stores indices and enums as int)
    Size,  ///< an integer in 0..2^53 (offsets, lengths, counts)
};

/// The kind of the number at a schema path: object members by name, array elements as "[]"
/// ("meshes[].primitives[].attributes.POSITION" -> Index). For tests and messages.
NumberKind numberKindAt(std::string_view schemaPath);

/// Walks the document once: every integer property of glTF 2.0's schema and of the extensions
/// Lantern reads is an integer in its range, every other number finite and within 1e30;
/// `extras`, accessors' `min`/`max` and extensions Lantern does not read are not looked at.
Result<void> checkAllNumbers(const nlohmann::json& doc, const Diagnostics& diag);

} // namespace lantern::gltf
