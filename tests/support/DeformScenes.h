// DeformScenes.h: small skinned and morphing scenes the tests build in code: a strip bent by
// a two-bone skin (optionally with its weights split over JOINTS_0 and JOINTS_1, 8
// influences), and a sphere whose morph target pushes it outwards.
#pragma once

#include <lantern/Scene.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::test {

/// Bone 1's rotation about +Y at `time`: 0 at t = 0, 90 degrees at t = 1 (LINEAR).
inline double stripBendAngle(double time) { return 1.5707963267948966 * std::clamp(time, 0.0, 1.0); }

/// Bone 1's weight at x: 0 up to x = 0.5, 1 from x = 1.5, linear between.
inline double stripWeight(double x) { return std::clamp(x - 0.5, 0.0, 1.0); }

/// Nodes: 0 "bone0" (root, at the origin), 1 "bone1" (child of 0 at x = 1, rotated about +Y
/// by stripBendAngle(t)), 2 "strip" (root, translated by (5, 5, 5), which skinning ignores),
/// drawing mesh 0 with skin 0. The strip spans x in [0, 2], y in [-0.25, 0.25], z = 0, normal
/// +Z, `segments` quads along x. With `eightInfluences` each weight is split in halves over
/// JOINTS_0 and JOINTS_1 (same result).
inline Scene makeSkinnedStrip(int segments = 8, bool eightInfluences = false) {
    Scene s;
    s.sourcePath = "test:skinned-strip";
    Primitive p;
    for (int i = 0; i <= segments; ++i)
        for (int r = 0; r < 2; ++r) {
            const double x = 2.0 * i / segments, y = r == 0 ? -0.25 : 0.25;
            p.positions.push_back(glm::vec3(float(x), float(y), 0.0f));
            p.normals.push_back(glm::vec3(0, 0, 1));
            const float w1 = float(stripWeight(x)), w0 = 1.0f - w1;
            if (eightInfluences) {
                p.joints0.push_back(glm::uvec4(0, 1, 0, 0));
                p.weights0.push_back(glm::vec4(w0 / 2, w1 / 2, 0, 0));
                p.joints1.push_back(glm::uvec4(1, 0, 1, 1));
                p.weights1.push_back(glm::vec4(w1 / 2, w0 / 2, 0, 0));
            } else {
                p.joints0.push_back(glm::uvec4(0, 1, 0, 0));
                p.weights0.push_back(glm::vec4(w0, w1, 0, 0));
            }
        }
    for (int i = 0; i < segments; ++i) {
        const std::uint32_t a = std::uint32_t(2 * i), b = a + 2, c = a + 3, d = a + 1;
        p.indices.insert(p.indices.end(), {a, b, c, a, c, d});
    }
    Material m;
    m.name = "strip";
    m.doubleSided = true;
    m.front.diffuse = {0.8, 0.6, 0.4, 1.0};
    m.front.specular = {0.5, 0.5, 0.5};
    m.front.shininess = 20.0;
    s.materials.push_back(m);
    p.material = 0;
    s.meshes.push_back(Mesh{"strip", {p}, {}});
    Node bone0;
    bone0.name = "bone0";
    bone0.children = {1};
    Node bone1;
    bone1.name = "bone1";
    bone1.translation = {1, 0, 0};
    Node strip;
    strip.name = "strip";
    strip.translation = {5, 5, 5};
    strip.mesh = 0;
    strip.skin = 0;
    s.nodes = {bone0, bone1, strip};
    Skin skin;
    skin.name = "two bones";
    skin.joints = {0, 1};
    skin.inverseBind = {glm::dmat4(1.0),
                        glm::translate(glm::dmat4(1.0), glm::dvec3(-1, 0, 0))};
    skin.skeleton = 0;
    s.skins.push_back(skin);
    Animation a;
    a.name = "bend";
    AnimationSampler smp;
    smp.interpolation = Interpolation::Linear;
    smp.times = {0.0, 1.0};
    const double h = stripBendAngle(1.0) / 2;
    smp.values = {glm::dvec4(0, 0, 0, 1), glm::dvec4(0, std::sin(h), 0, std::cos(h))};
    a.samplers.push_back(smp);
    a.channels.push_back({1, AnimationPath::Rotation, 0});
    s.animations.push_back(a);
    s.roots.push_back(SceneRoot{"skin", {0, 2}, std::nullopt});
    return s;
}

/// Adds a sphere (radius 0.5 at `at`) whose one morph target moves every vertex 0.3 along its
/// normal, its weight animated by `sampler` (one weight per key); returns the node index.
inline int addMorphingSphere(Scene& s, const glm::dvec3& at, AnimationSampler sampler) {
    Primitive p = makeSphere(0.5, 16, 8);
    MorphTarget t;
    for (const glm::vec3& n : p.normals) t.positions.push_back(0.3f * n);
    p.targets.push_back(t);
    p.material = s.materials.empty() ? -1 : 0;
    s.meshes.push_back(Mesh{"morph", {p}, {0.25}});
    Node n;
    n.name = "morph";
    n.translation = at;
    n.mesh = int(s.meshes.size()) - 1;
    s.nodes.push_back(n);
    const int node = int(s.nodes.size()) - 1;
    s.roots[0].nodes.push_back(node);
    sampler.weightCount = 1;
    Animation a;
    a.name = "inflate";
    a.samplers.push_back(sampler);
    a.channels.push_back({node, AnimationPath::Weights, 0});
    s.animations.push_back(a);
    return node;
}

} // namespace lantern::test
