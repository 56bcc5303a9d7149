// The C++ mirrors in gpu/GpuLayouts.h against the member offsets in the SPIR-V that ships
// (the embedded blobs), so a change on either side without the other fails here.
#include "gpu/Clusters.h"
#include "gpu/GpuLayouts.h"

#include "ShaderBlobs.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <map>
#include <string>

namespace {

using lantern::shaders::allShaderBlobs;
using lantern::shaders::ShaderBlob;
using lantern::shaders::ShaderId;
using lantern::shaders::shaderBlob;

// Struct name -> member name -> byte offset, from OpName / OpMemberName / OpMemberDecorate.
using Layouts = std::map<std::string, std::map<std::string, std::uint32_t>>;

std::string readString(const std::uint32_t* words, std::size_t count) {
    std::string s;
    for (std::size_t i = 0; i < count; ++i)
        for (int b = 0; b < 4; ++b) {
            const char c = char((words[i] >> (8 * b)) & 0xFF);
            if (c == 0) return s;
            s += c;
        }
    return s;
}

Layouts parse(const std::uint32_t* code, std::size_t count) {
    constexpr std::uint32_t kOpName = 5, kOpMemberName = 6, kOpMemberDecorate = 72, kOffset = 35;
    std::map<std::uint32_t, std::string> names;
    std::map<std::uint32_t, std::map<std::uint32_t, std::string>> memberNames;
    std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> offsets;
    for (std::size_t i = 5; i < count;) {
        const std::uint32_t op = code[i] & 0xFFFF, len = code[i] >> 16;
        if (len == 0) break;
        if (op == kOpName) names[code[i + 1]] = readString(code + i + 2, len - 2);
        if (op == kOpMemberName)
            memberNames[code[i + 1]][code[i + 2]] = readString(code + i + 3, len - 3);
        if (op == kOpMemberDecorate && code[i + 3] == kOffset) offsets[code[i + 1]][code[i + 2]] = code[i + 4];
        i += len;
    }
    Layouts out;
    for (const auto& [id, members] : offsets)
        for (const auto& [index, offset] : members) out[names[id]][memberNames[id][index]] = offset;
    return out;
}

Layouts allLayouts() {
    Layouts merged;
    for (const auto& blob : allShaderBlobs()) {
        for (const auto& [type, members] : parse(blob.words, blob.wordCount))
            for (const auto& [member, offset] : members) {
                auto [it, inserted] = merged[type].emplace(member, offset);
                EXPECT_EQ(it->second, offset) << type << "." << member << " differs between shaders ("
                                              << blob.name << ")";
                (void)inserted;
            }
    }
    return merged;
}

struct Row {
    const char* type;
    const char* member;
    std::size_t offset;  // offsetof in the C++ mirror
};

#define LANTERN_ROW(T, M) Row{#T, #M, offsetof(lantern::gpu::T, M)}
// A mirror whose GLSL struct (or member) has another name (the cluster-culling pass's).
#define LANTERN_ROW_AS(T, GLSL, M, GLSL_M) Row{GLSL, GLSL_M, offsetof(lantern::gpu::T, M)}

TEST(GpuLayouts, MirrorsMatchTheShippedSpirv) {
    const Layouts layouts = allLayouts();
    const Row rows[] = {
        LANTERN_ROW(FrameBlock, clipFromView),   LANTERN_ROW(FrameBlock, globalAmbient),
        LANTERN_ROW(FrameBlock, lightCount),     LANTERN_ROW(FrameBlock, viewIndex),
        LANTERN_ROW(FrameBlock, shadowMaps),     LANTERN_ROW(FrameBlock, shadowParams),
        LANTERN_ROW(ShadowData, clipFromView),   LANTERN_ROW(ShadowData, params),
        LANTERN_ROW(ShadowData, depth),
        LANTERN_ROW(LightData, position),        LANTERN_ROW(LightData, ambient),
        LANTERN_ROW(LightData, diffuse),         LANTERN_ROW(LightData, specular),
        LANTERN_ROW(LightData, spotDirection),   LANTERN_ROW(LightData, attenuation),
        LANTERN_ROW(LightData, spot),            LANTERN_ROW(LightData, info),
        LANTERN_ROW(MaterialSideData, ambient),  LANTERN_ROW(MaterialSideData, diffuse),
        LANTERN_ROW(MaterialSideData, specular), LANTERN_ROW(MaterialSideData, emission),
        LANTERN_ROW(MaterialData, front),        LANTERN_ROW(MaterialData, back),
        LANTERN_ROW(MaterialData, params),       LANTERN_ROW(MaterialData, uvRow0),
        LANTERN_ROW(MaterialData, uvRow1),       LANTERN_ROW(MaterialData, pbrBase),
        LANTERN_ROW(MaterialData, pbrParams),    LANTERN_ROW(MaterialData, mapUv),
        LANTERN_ROW(DrawBlock, viewFromModel),
        LANTERN_ROW(DrawBlock, normalMatrix),    LANTERN_ROW(DrawBlock, materialIndex),
        LANTERN_ROW(DrawBlock, drawIndex),       LANTERN_ROW(DrawBlock, flags),
        LANTERN_ROW(DrawBlock, flatJob),
        LANTERN_ROW(InstanceData, viewFromModel), LANTERN_ROW(InstanceData, normalMatrix),
        LANTERN_ROW(FlatJob, viewFromModel),     LANTERN_ROW(FlatJob, normalMatrix),
        LANTERN_ROW(FlatJob, materialIndex),     LANTERN_ROW(FlatJob, drawIndex),
        LANTERN_ROW(FlatJob, flags),             LANTERN_ROW(FlatJob, flatBase),
        LANTERN_ROW(FlatJob, count),             LANTERN_ROW(FlatJob, indices),
        LANTERN_ROW(FlatJob, positions),         LANTERN_ROW(FlatJob, deformed),
        LANTERN_ROW(FlatJob, colors),            LANTERN_ROW(FlatJob, cull),
        LANTERN_ROW(FlatJob, writeNormals),      LANTERN_ROW(FlatJob, view),
        LANTERN_ROW(FlatJob, viewport),          LANTERN_ROW(FlatJob, texcoords),
        LANTERN_ROW(FlatJob, texcoords1),
        LANTERN_ROW(DeformJob, count),           LANTERN_ROW(DeformJob, flatMode),
        LANTERN_ROW(DeformJob, vertexCount),     LANTERN_ROW(DeformJob, position),
        LANTERN_ROW(DeformJob, normal),          LANTERN_ROW(DeformJob, joints),
        LANTERN_ROW(DeformJob, weights),         LANTERN_ROW(DeformJob, influences),
        LANTERN_ROW(DeformJob, targets),         LANTERN_ROW(DeformJob, targetCount),
        LANTERN_ROW(DeformJob, indices),         LANTERN_ROW(DeformJob, matrices),
        LANTERN_ROW(DeformJob, morphWeights),    LANTERN_ROW(DeformJob, outPosition),
        LANTERN_ROW(DeformJob, outNormal),       LANTERN_ROW(DeformJob, outCentroid),
        LANTERN_ROW_AS(ClusterData, "Cluster", sphere, "sphere"),
        LANTERN_ROW_AS(ClusterData, "Cluster", apex, "apex"),
        LANTERN_ROW_AS(ClusterData, "Cluster", axis, "axis"),
        LANTERN_ROW_AS(ClusterData, "Cluster", firstIndex, "range"),
        LANTERN_ROW_AS(CullLevel, "Level", error, "error"),
        LANTERN_ROW_AS(CullLevel, "Level", firstCluster, "firstCluster"),
        LANTERN_ROW_AS(CullLevel, "Level", clusterCount, "clusterCount"),
        LANTERN_ROW_AS(CullLevel, "Level", padding, "padding"),
        LANTERN_ROW_AS(CullView, "View", planes, "planes"),
        LANTERN_ROW_AS(CullView, "View", projection, "projection"),
        LANTERN_ROW_AS(CullRecord, "Record", viewFromModel, "viewFromModel"),
        LANTERN_ROW_AS(CullRecord, "Record", normalMatrix, "normalMatrix"),
        LANTERN_ROW_AS(CullRecord, "Record", sphere, "sphere"),
        LANTERN_ROW_AS(CullRecord, "Record", view, "view"),
        LANTERN_ROW_AS(CullRecord, "Record", flags, "flags"),
        LANTERN_ROW_AS(CullRecord, "Record", firstCommand, "firstCommand"),
        LANTERN_ROW_AS(CullRecord, "Record", slots, "slots"),
        LANTERN_ROW_AS(CullRecord, "Record", firstInstance, "firstInstance"),
        LANTERN_ROW_AS(CullRecord, "Record", levelCount, "levelCount"),
        LANTERN_ROW_AS(CullRecord, "Record", lodCommand, "lodCommand"),
        LANTERN_ROW_AS(CullRecord, "Record", drawRecords, "drawRecords"),
        LANTERN_ROW_AS(CullRecord, "Record", scale, "scale"),
        LANTERN_ROW_AS(CullRecord, "Record", indexBase, "indexBase"),
        LANTERN_ROW_AS(CullRecord, "Record", lodSlots, "lodSlots"),
        LANTERN_ROW_AS(CullRecord, "Record", countIndex, "countIndex"),
        LANTERN_ROW_AS(CullRecord, "Record", levels, "levels"),
    };
    for (const Row& r : rows) {
        SCOPED_TRACE(std::string(r.type) + "." + r.member);
        auto type = layouts.find(r.type);
        ASSERT_NE(type, layouts.end()) << "struct not found in any shader";
        auto member = type->second.find(r.member);
        ASSERT_NE(member, type->second.end()) << "member not found";
        EXPECT_EQ(member->second, r.offset);
    }
}

TEST(GpuLayouts, EveryShaderMemberIsMirrored) {
    // A member added to a shader block but not to the C++ mirror is caught here.
    const std::map<std::string, std::size_t> expectedCounts = {
        {"FrameBlock", 7}, {"ShadowData", 3}, {"LightData", 8}, {"MaterialSideData", 4}, {"MaterialData", 8}, {"DrawBlock", 6},
        {"InstanceData", 2},
        {"DeformJob", 16}, {"FlatJob", 17},
        {"Cluster", 4}, {"Level", 4}, {"View", 2}, {"Record", 16}};
    const Layouts layouts = allLayouts();
    for (const auto& [type, count] : expectedCounts) {
        auto it = layouts.find(type);
        ASSERT_NE(it, layouts.end()) << type;
        EXPECT_EQ(it->second.size(), count) << type << " has members the C++ mirror does not list";
    }
}

TEST(GpuLayouts, PushConstantsFitTheGuaranteedMinimum) {
    EXPECT_LE(sizeof(lantern::gpu::DrawBlock), 128u);
    EXPECT_LE(sizeof(lantern::gpu::DeformJob), 128u);
}

} // namespace

namespace {

// Calls `f(op, operands, operandCount)` for each instruction of a SPIR-V module.
template <typename F> void forEachInstruction(const ShaderBlob& blob, F&& f) {
    for (std::size_t i = 5; i < blob.wordCount;) {
        const std::uint32_t op = blob.words[i] & 0xFFFF, len = blob.words[i] >> 16;
        if (len == 0) break;
        f(op, blob.words + i + 1, std::size_t(len - 1));
        i += len;
    }
}

// Whether the module declares the built-in `builtIn` (glslang declares only those it reads).
bool declaresBuiltIn(const ShaderBlob& blob, std::uint32_t builtIn) {
    constexpr std::uint32_t kOpDecorate = 71, kBuiltIn = 11;
    bool found = false;
    forEachInstruction(blob, [&](std::uint32_t op, const std::uint32_t* w, std::size_t n) {
        found |= op == kOpDecorate && n >= 3 && w[1] == kBuiltIn && w[2] == builtIn;
    });
    return found;
}

// The module's input variables at a location (a vertex shader's attributes).
std::size_t locatedInputs(const ShaderBlob& blob) {
    constexpr std::uint32_t kOpDecorate = 71, kLocation = 30, kOpVariable = 59, kInput = 1;
    std::map<std::uint32_t, bool> located;
    std::size_t count = 0;
    forEachInstruction(blob, [&](std::uint32_t op, const std::uint32_t* w, std::size_t n) {
        if (op == kOpDecorate && n >= 2 && w[1] == kLocation) located[w[0]] = true;
        if (op == kOpVariable && n >= 3 && w[2] == kInput && located.count(w[1])) ++count;
    });
    return count;
}

} // namespace

// Per-triangle flat draws pull their corners from storage buffers (no vertex attributes) and
// pass the triangle's record as a varying: on llvmpipe a fragment shader that reads
// gl_PrimitiveID sends every draw through a primitive assembler that de-indexes it on the CPU
// (docs/performance.md). The AOV variant still writes the primitive id AOV, as every mode does.
TEST(GpuLayouts, PerTriangleFlatDrawsHaveNoAttributesAndReadNoPrimitiveIdOutsideAovs) {
    constexpr std::uint32_t kPrimitiveId = 7;
    EXPECT_EQ(locatedInputs(shaderBlob(ShaderId::flatprim_vert)), 0u);
    EXPECT_GT(locatedInputs(shaderBlob(ShaderId::gouraud_vert)), 0u) << "attributes not seen";
    EXPECT_FALSE(declaresBuiltIn(shaderBlob(ShaderId::flatprim_frag), kPrimitiveId));
    EXPECT_FALSE(declaresBuiltIn(shaderBlob(ShaderId::gouraud_frag), kPrimitiveId));
    EXPECT_TRUE(declaresBuiltIn(shaderBlob(ShaderId::flatprim_aov_frag), kPrimitiveId))
        << "the primitive id not seen";
}
