// libFuzzer target that mutates glTF documents as documents: a custom mutator parses the input
// as JSON and changes one value of the tree the way a hostile or broken exporter would (an
// index one past the end or far beyond it, a count of 2^32, a huge or negative number, an
// empty or duplicated array, a missing or transplanted member, a subtree copied from another
// place), then the loader and everything a render does before the GPU run on the result
// (FuzzLoad.h, as in GltfFuzz.cpp). Inputs that are not JSON fall back to libFuzzer's byte mutations, so GLB
// and garbage seeds still work. Seeds: tests/fuzz/seeds/ (small valid scenes with every
// feature, buffers in data: URIs) and what scripts/fuzz.sh adds.
#include "FuzzLoad.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);

namespace {

using json = nlohmann::json;

// Every value of the tree, depth first (the root included).
void collect(json& v, std::vector<json*>& out) {
    out.push_back(&v);
    if (v.is_object() || v.is_array())
        for (json& child : v) collect(child, out);
}

// Numbers a careless or hostile writer puts where a small index, count or factor belongs.
json hostileNumber(std::mt19937& rng, const json& old) {
    static const double numbers[] = {0.0, -1.0, 1.0, 2.0, 3.0, 255.0, 256.0, 65535.0, 65536.0,
                                     2147483647.0, 2147483648.0, 4294967295.0, 4294967296.0,
                                     -2147483649.0, 1e300, -1e300, 1e-300, 0.5, 1e9, 9007199254740993.0};
    std::uniform_int_distribution<int> pick(0, int(std::size(numbers)) + 2);
    const int k = pick(rng);
    if (k < int(std::size(numbers))) {
        const double d = numbers[k];
        if (std::abs(d) < 9e18 && d == std::floor(d)) return std::int64_t(d);
        return d;
    }
    if (old.is_number_integer()) {  // next to the old value: off-by-one indices
        const std::int64_t i = old.get<std::int64_t>();
        return k == int(std::size(numbers)) ? i + 1 : i - 1;
    }
    return old.is_number() ? json(old.get<double>() * -3.0) : json(7);
}

json hostileString(std::mt19937& rng) {
    static const char* strings[] = {"", "data:", "data:application/octet-stream;base64,AAAA",
                                    "../outside.bin", "/etc/passwd", "a.bin", "%2e%2e/x",
                                    "KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                    "KHR_texture_transform", "BLEND", "MASK", "STEP", "CUBICSPLINE",
                                    "weights", "translation", "VEC3", "MAT4", "SCALAR"};
    std::uniform_int_distribution<int> pick(0, int(std::size(strings)));
    const int k = pick(rng);
    if (k < int(std::size(strings))) return strings[k];
    return std::string(4096, 'x');
}

// One change to the value at `target`; `all` lists every value of the document (for copies).
void mutateValue(json& target, const std::vector<json*>& all, std::mt19937& rng) {
    std::uniform_int_distribution<int> op(0, 5);
    std::uniform_int_distribution<std::size_t> anyValue(0, all.size() - 1);
    switch (op(rng)) {
    case 0:  // a hostile scalar of the same kind, else a number
        if (target.is_string()) target = hostileString(rng);
        else target = hostileNumber(rng, target);
        return;
    case 1:  // arrays: drop, duplicate or empty; objects: drop a member
        if (target.is_array() && !target.empty()) {
            std::uniform_int_distribution<std::size_t> at(0, target.size() - 1);
            const std::size_t i = at(rng);
            if (rng() % 3 == 0) target.clear();
            else if (rng() % 2 == 0) target.erase(i);
            else target.push_back(json(target[i]));
        } else if (target.is_object() && !target.empty()) {
            std::uniform_int_distribution<std::size_t> at(0, target.size() - 1);
            auto it = target.begin();
            std::advance(it, std::ptrdiff_t(at(rng)));
            target.erase(it.key());
        }
        return;
    case 2: {  // a copy of another value of the document (a transplanted subtree)
        json copy = *all[anyValue(rng)];
        if (copy.dump().size() < 1 << 16) target = std::move(copy);
        return;
    }
    case 3:  // an object gains a member copied from elsewhere (children, extensions, ...)
        if (target.is_object()) {
            json* from = all[anyValue(rng)];
            if (from->is_object() && !from->empty()) {
                auto it = from->begin();
                std::advance(it, std::ptrdiff_t(rng() % from->size()));
                target[it.key()] = it.value();
            }
        }
        return;
    case 4:  // the type changes
        if (target.is_number()) target = json::array({target});
        else if (target.is_array()) target = json::object();
        else if (target.is_object()) target = 0;
        else target = nullptr;
        return;
    default:  // an array grows by many copies of one element (counts, cycles, depth)
        if (target.is_array() && !target.empty() && target.size() < 4096) {
            const json element = target[rng() % target.size()];
            for (int i = 0; i < 64; ++i) target.push_back(element);
        }
        return;
    }
}

} // namespace

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,
                                               std::size_t maxSize, unsigned int seed) {
    json doc = json::parse(data, data + size, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return LLVMFuzzerMutate(data, size, maxSize);
    std::mt19937 rng(seed);
    const int changes = 1 + int(rng() % 3);
    for (int c = 0; c < changes; ++c) {
        std::vector<json*> all;
        collect(doc, all);
        mutateValue(*all[rng() % all.size()], all, rng);
    }
    const std::string out = doc.dump();
    if (out.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
    std::memcpy(data, out.data(), out.size());
    return out.size();
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lantern::fuzz::loadAndPlan(data, size);
    return 0;
}
