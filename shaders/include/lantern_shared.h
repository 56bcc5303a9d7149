// lantern_shared.h: the facts shared by GLSL and C++ (binding numbers, attribute locations,
// specialisation-constant ids, enum values, numeric guards). Only #defines, so it is valid in
// both languages. Change a number here and nowhere else.
#ifndef LANTERN_SHARED_H
#define LANTERN_SHARED_H

// Descriptor sets and bindings.
#define LANTERN_SET_FRAME 0
#define LANTERN_BINDING_FRAME 0      // uniform FrameBlock (dynamic offset, one per view)
#define LANTERN_BINDING_LIGHTS 1     // buffer LightBlock (dynamic offset, one per view)
#define LANTERN_BINDING_MATERIALS 2  // buffer MaterialBlock
#define LANTERN_BINDING_FLAT_COLORS 3   // buffer: per-triangle flat colours (flatlight.comp)
#define LANTERN_BINDING_FLAT_NORMALS 4  // buffer: per-triangle eye normals (frames with AOVs)
#define LANTERN_BINDING_GUARD 5         // buffer: the frame's output guard word (guard.glsl)
#define LANTERN_BINDING_LIGHTS_UNIFORM 6  // uniform: the same lights as LIGHTS, for up to
                                          // LANTERN_UNIFORM_LIGHTS of them (SC_LIGHTS_UNIFORM)
#define LANTERN_BINDING_INSTANCES 7     // buffer: the instanced draws' transforms (instance.glsl)
#define LANTERN_BINDING_SHADOW_MAP 8    // sampler2DArrayShadow: the frame's shadow maps (shadows.glsl)
#define LANTERN_BINDING_SHADOWS 9       // buffer: per view and map, its clip-from-view (shadows.glsl)
#define LANTERN_BINDING_FRAGMENT_LISTS 10  // buffer: exact transparency's per-pixel lists (oit.glsl)
#define LANTERN_BINDING_WEIGHTED_ACCUM 11  // image2D rgba32f: weighted transparency's sums (oit.glsl)
#define LANTERN_BINDING_WEIGHTED_REVEAL 12 // image2D r32f: weighted transparency's revealage
#define LANTERN_BINDING_SHADOW_DEPTH 13    // sampler2DArray: the shadow maps' depths (PCSS's blocker search)
#define LANTERN_SET_TEXTURE 1
#define LANTERN_BINDING_BASE_COLOR 0 // sampler2D, the material's base-colour texture
#define LANTERN_BINDING_METALLIC_ROUGHNESS 1  // sampler2D: B metallic, G roughness (linear)
#define LANTERN_BINDING_NORMAL 2     // sampler2D: tangent-space normal map (linear)
#define LANTERN_BINDING_OCCLUSION 3  // sampler2D: R ambient occlusion (linear)
#define LANTERN_BINDING_EMISSIVE 4   // sampler2D: emissive colour (sRGB)
#define LANTERN_TEXTURE_BINDINGS 5

// The deformation pre-pass (shaders/deform.comp): its own set, used by no graphics pipeline.
#define LANTERN_BINDING_DEFORM_INPUT 0   // buffer: the scene's deformation inputs
#define LANTERN_BINDING_DEFORM_PARAMS 1  // buffer: this frame's joint matrices, morph weights
#define LANTERN_BINDING_DEFORM_OUTPUT 2  // buffer: deformed streams, read as vertex buffers
#define LANTERN_DEFORM_GROUP 64          // invocations per workgroup
#define LANTERN_DEFORM_NONE 0xFFFFFFFFu  // an absent offset

// The per-triangle flat-lighting pre-pass (shaders/flatlight.comp): its inputs in their own set
// (the frame set's bindings give it the lights and materials and take its results).
#define LANTERN_SET_FLAT 2
#define LANTERN_BINDING_FLAT_GEOMETRY 0  // buffer: the scene's geometry (positions, colours, indices)
#define LANTERN_BINDING_FLAT_DEFORMED 1  // buffer: this frame's deformed streams
#define LANTERN_BINDING_FLAT_JOBS 2      // buffer: one FlatJob per flat triangle draw
#define LANTERN_BINDING_FLAT_INDICES 3   // buffer: the draws' index lists, written by the pass
#define LANTERN_FLAT_GROUP 64            // invocations (triangles) per workgroup
#define LANTERN_FLAT_CULL_BACK 1u        // FlatJob.cull: the draw culls back faces
#define LANTERN_FLAT_FRONT_CLOCKWISE 2u  // FlatJob.cull: clockwise triangles are front

// The cluster-culling pre-pass (shaders/cull.comp, gpu/Clusters.h): its own set, used by no
// graphics pipeline.
#define LANTERN_BINDING_CULL_CLUSTERS 0  // buffer: the scene's clusters (bounds, cones, ranges)
#define LANTERN_BINDING_CULL_RECORDS 1   // buffer: this frame's records (draw x instance x view)
#define LANTERN_BINDING_CULL_COMMANDS 2  // buffer: the indirect draws the pass writes
#define LANTERN_BINDING_CULL_COUNTS 3    // buffer: triangles kept (the frame's statistics)
#define LANTERN_BINDING_CULL_VIEWS 4     // buffer: per view, its clip volume's planes
#define LANTERN_CULL_GROUP 64            // invocations (records) per workgroup
#define LANTERN_CLUSTER_TRIANGLES 128    // triangles per cluster (the last of a mesh: fewer)
#define LANTERN_CULL_CONE 1u             // CullRecord.flags: the back-facing cone test applies
#define LANTERN_CULL_MAX_LEVELS 8        // levels of detail per mesh, the full one included

// Vertex attribute locations; each attribute has its own vertex-buffer binding of the same
// number (non-interleaved streams, so absent attributes can be bound to a stride-0 default).
#define LANTERN_LOC_POSITION 0
#define LANTERN_LOC_NORMAL 1
#define LANTERN_LOC_COLOR 2
#define LANTERN_LOC_TEXCOORD 3
#define LANTERN_LOC_CENTROID 4       // flat shading only: the triangle's centroid
#define LANTERN_VERTEX_BINDINGS 5    // the bindings of flat shading's per-corner draws
#define LANTERN_LOC_TANGENT 5        // phong (mesh.vert) only: TANGENT, zero when absent
#define LANTERN_LOC_TEXCOORD1 6      // the second texture-coordinate set, zero when absent

// Fragment outputs (colour attachments of the render pass, in this order).
#define LANTERN_OUT_COLOR 0
#define LANTERN_OUT_NORMAL_DEPTH 1   // AOV variants: float bits of the eye normal and depth
#define LANTERN_OUT_ID 2             // AOV variants: draw index + 1, primitive id
#define LANTERN_OUT_SURFACE 3        // AOV variants: float bits of TEXCOORD_0 (u, v), range, 0
#define LANTERN_OUT_COUNT_AOV 4
// The AOV background: the depth (normal-depth .w) and range (surface .z) of a pixel that no
// surface covers, as float bits: FLT_MAX.
#define LANTERN_FLT_MAX_BITS 0x7F7FFFFFu

// Specialisation constants: the features a pipeline variant compiles in.
#define LANTERN_SC_LIGHT_TYPES 0     // bit mask of LANTERN_LIGHT_BIT_*
#define LANTERN_SC_GL_ATTENUATION 1  // a GL light has attenuation other than (1,0,0)
#define LANTERN_SC_GL_SPOT 2         // a GL spot light with a cone (cutoff != 180)
#define LANTERN_SC_GLTF_FALLOFF 3    // a glTF-form point or spot light
#define LANTERN_SC_SPECULAR 4        // LANTERN_SPECULAR_*
#define LANTERN_SC_LOCAL_VIEWER 5
#define LANTERN_SC_TWO_SIDED 6
#define LANTERN_SC_VERTEX_COLOR 7
#define LANTERN_SC_TEXTURE 8
#define LANTERN_SC_ALPHA_MASK 9
#define LANTERN_SC_CLAMP 10          // LANTERN_CLAMP_*
#define LANTERN_SC_UNLIT 11
#define LANTERN_SC_AMBIENT_FOLLOWS_DIFFUSE 12
#define LANTERN_SC_OPAQUE 13         // write alpha 1 (glTF OPAQUE and MASK)
#define LANTERN_SC_MAPS 14           // bit mask of LANTERN_MAP_*: the material maps compiled in
#define LANTERN_SC_UNROLLED_LIGHTS 15  // 0: a loop over frame.lightCount; n: exactly n lights
#define LANTERN_SC_LIGHT_KINDS 16    // with n lights unrolled: light i's kind in bits 4i..4i+3
#define LANTERN_SC_LIGHTS_UNIFORM 17  // 1: the lights are read from LIGHTS_UNIFORM, not LIGHTS
#define LANTERN_SC_INSTANCED 18      // 1: the draw's transforms are per instance (instance.glsl)
#define LANTERN_SC_SHADOWS 19        // LANTERN_SHADOW_*: how shadow maps are read (none: no light casts)
#define LANTERN_SC_COUNT 20

#define LANTERN_SHADOW_NONE 0u
#define LANTERN_SHADOW_HARDWARE 1u     // one comparison with the device's 2 x 2 filter
#define LANTERN_SHADOW_PCF 2u          // kernel x kernel filtered comparisons
#define LANTERN_SHADOW_PCSS 3u         // blocker search, then PCF over the penumbra's width
#define LANTERN_MAX_CASCADES 8         // a directional light's maps at most (ShadowOptions::cascades)

// Material maps (MaterialData.params.y holds the material's, as a float).
#define LANTERN_MAP_METALLIC_ROUGHNESS 1u
#define LANTERN_MAP_NORMAL 2u
#define LANTERN_MAP_OCCLUSION 4u
#define LANTERN_MAP_EMISSIVE 8u
#define LANTERN_MAP_ALL 15u
// Map bit << 4: that map reads the second texture-coordinate set (Primitive::texcoords1).
#define LANTERN_MAP_SECOND_SET_SHIFT 4u
#define LANTERN_MAP_SECOND_SETS 240u

#define LANTERN_LIGHT_BIT_DIRECTIONAL 1
#define LANTERN_LIGHT_BIT_POINT 2
#define LANTERN_LIGHT_BIT_SPOT 4

#define LANTERN_SPECULAR_NONE 0
#define LANTERN_SPECULAR_BLINN 1
#define LANTERN_SPECULAR_PHONG 2

#define LANTERN_CLAMP_NONE 0
#define LANTERN_CLAMP_FRAGMENT 1     // --clamp: the final colour
#define LANTERN_CLAMP_GL 2           // --gl-compat: each lit colour where it is computed

// LightData.info.x
#define LANTERN_LIGHT_DIRECTIONAL 0
#define LANTERN_LIGHT_POINT 1
#define LANTERN_LIGHT_SPOT 2
// LightData.info.y
#define LANTERN_FALLOFF_GL 0
#define LANTERN_FALLOFF_GLTF 1
// Unrolled lights (LANTERN_SC_UNROLLED_LIGHTS): a frame with at most this many lights is lit
// by code with one copy of the light's terms per light, at a constant index, each for its
// light's kind: type | falloff << 2 (4 bits a light in LANTERN_SC_LIGHT_KINDS).
#define LANTERN_MAX_UNROLLED_LIGHTS 8
// The most lights a frame reads from a uniform buffer: 16 KiB (128-byte LightData), the least
// maxUniformBufferRange Vulkan allows. More are read from the storage buffer.
#define LANTERN_UNIFORM_LIGHTS 128
#define LANTERN_LIGHT_KIND_BITS 4u
#define LANTERN_LIGHT_KIND_ANY 0xFFFFFFFFu  // the loop: type and falloff read from the light

// Numeric guards, shared by the shaders and the CPU reference so both take the same branch.
// GL attenuation 1/(kc + kl d + kq d^2) is evaluated as 1/max(denominator, this): a light on
// the surface with kc = 0 gives 1e30, finite.
#define LANTERN_MIN_ATTENUATION_DENOMINATOR 1e-30
// glTF falloff 1/max(d^2, this) (scene-format.md section 1).
#define LANTERN_MIN_GLTF_DISTANCE_SQUARED 1e-4

// The output guard (shaders/include/guard.glsl): a lit colour with a NaN, a part of magnitude
// above this or an alpha outside [0, 1], where the vertex stage or the flat pre-pass makes it,
// trips it, and the host then checks the whole picture. The fragment stage interpolates
// (a convex mix) and adds the two parts, the textured one times a texel in [0, 1]; blends mix
// (alpha in [0, 1]) and resolves average. So an output stays within twice this, far from a
// float's overflow, and a frame that did not trip the guard needs no host check.
#define LANTERN_GUARD_BOUND 1e35

// The metallic-roughness mapping's shininess range (scene-format-support.md, Materials).
#define LANTERN_PBR_MIN_SHININESS 1.0
#define LANTERN_PBR_MAX_SHININESS 1e4

// Exact transparency's fragment lists (shaders/include/oit.glsl, gpu/Transparency.h): a
// header of LANTERN_OIT_HEADER_WORDS words, one head word per pixel, then nodes of
// LANTERN_OIT_NODE_WORDS words (next, depth, r, g, b, alpha, sample mask). The resolve composites at most
// LANTERN_OIT_MAX_LAYERS fragments a pixel, the nearest.
#define LANTERN_OIT_HEADER_WORDS 8
#define LANTERN_OIT_NODE_WORDS 7
#define LANTERN_OIT_MAX_LAYERS 32
#define LANTERN_OIT_END 0xFFFFFFFFu
// Header words.
#define LANTERN_OIT_WIDTH 0        // the target's width in pixels (heads are row-major)
#define LANTERN_OIT_CAPACITY 1     // nodes the buffer holds
#define LANTERN_OIT_COUNT 2        // nodes asked for this frame (above CAPACITY: some were lost)
#define LANTERN_OIT_TRUNCATED 3    // pixels with more than LANTERN_OIT_MAX_LAYERS fragments
#define LANTERN_OIT_NEARER_GREATER 4  // 1: reversed Z (a nearer fragment has the greater depth)
#define LANTERN_OIT_SAMPLES 5      // samples per pixel (each composites the fragments covering it)
#define LANTERN_OIT_NODES 6        // the word where the nodes start (after the heads)

// Limits.
#define LANTERN_MAX_LIGHTS 65536

#endif
