// Cryptomatte: the name hashes of the Cryptomatte specification 1.2.0 (Psyop; Friedman and
// Jones, 2015), which Nuke, Blender and other compositors read as mattes. docs/aovs.md.
#pragma once

#include <lantern/Export.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace lantern {

/// MurmurHash3_x86_32 (Austin Appleby's reference) of `bytes` with `seed`.
LANTERN_API std::uint32_t murmurHash3_32(std::string_view bytes, std::uint32_t seed = 0) noexcept;

/// The bits of the float Cryptomatte stores for `hash`: the hash itself, except that when its
/// exponent bits (23..30) are all 0 or all 1 bit 23 is flipped, so the float is never
/// denormal, zero, infinite or NaN.
LANTERN_API std::uint32_t cryptomatteId(std::uint32_t hash) noexcept;

/// The float id of `name` (cryptomatteId(murmurHash3_32(name)) read as a float).
LANTERN_API float cryptomatteFloat(std::string_view name) noexcept;

/// The key of a layer's header attributes (cryptomatte/<key>/...): the first 7 hex digits of
/// murmurHash3_32(layerName), lower case.
LANTERN_API std::string cryptomatteKey(std::string_view layerName);

} // namespace lantern
