// The AOV names shared by the command line and the Python module (docs/aovs.md).
#include <lantern/Options.h>

#include <utility>

namespace lantern {

const char* aovNames() noexcept {
    return "depth, range, normal, world_normal, uv, instance, primitive, material, semantic, "
           "crypto_object, crypto_material";
}

bool enableAov(AovSet& aovs, std::string_view name) noexcept {
    static constexpr std::pair<std::string_view, bool AovSet::*> kNames[] = {
        {"depth", &AovSet::depth},         {"range", &AovSet::range},
        {"normal", &AovSet::normal},       {"world_normal", &AovSet::worldNormal},
        {"uv", &AovSet::uv},               {"instance", &AovSet::instance},
        {"primitive", &AovSet::primitive}, {"material", &AovSet::material},
        {"semantic", &AovSet::semantic},   {"crypto_object", &AovSet::cryptoObject},
        {"crypto_material", &AovSet::cryptoMaterial}};
    for (const auto& [known, member] : kNames)
        if (name == known) {
            aovs.*member = true;
            return true;
        }
    return false;
}

} // namespace lantern
