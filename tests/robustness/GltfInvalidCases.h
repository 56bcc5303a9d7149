// GltfInvalidCases.h: the expected outcome for every file of ../shared/assets/gltf-invalid (the
// Khronos glTF-Validator's negative cases): refused (object path and a fragment of the message)
// or loaded safely (a fragment of the warning that says what was skipped or repaired).
#pragma once

namespace lantern::test {

struct InvalidCase {
    const char* file;      ///< relative to assets/gltf-invalid
    bool refused;          ///< true: refused; false: loaded safely
    const char* object;    ///< refused: Error::object
    const char* fragment;  ///< refused: in Error::message; loaded: in a warning ("" none expected)
};

/// The fragment of a loaded case whose file draws nothing (lantern::nothingToDraw says why).
inline constexpr const char kDrawsNothing[] = "(draws nothing)";

// clang-format off
inline constexpr InvalidCase kInvalidCases[] = {
    // Refused for the defect the case is about (or, where tinygltf stops first, for the first
    // defect on the way: "not a readable glTF file" with tinygltf's reason).
    {"base/data/accessor/alignment.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/accessor/empty_object.gltf", true, "", "not a readable glTF file: 'componentType' property is missing in Acces"},
    {"base/data/accessor/float_normalized.gltf", true, "accessors[0].normalized", "only BYTE, UNSIGNED_BYTE, SHORT and UNSIGNED_SHORT may be normalized, "},
    {"base/data/accessor/invalid_sparse_count_and_stride.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/accessor/matrix_alignment.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/accessor/small_stride.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/accessor/unresolved_bufferviews.gltf", true, "accessors[0].bufferView", "bufferView 0 does not exist (the file has 0)"},
    {"base/data/accessor_data/invalid_elements_float.gltf", true, "accessors[0]", "element 0 component 0 is not a finite number (infinite)"},
    {"base/data/animation/channel_node_matrix.gltf", true, "animations[0].channels[0].target.node", "node 0 has a matrix; only translation/rotation/scale nodes can be anim"},
    {"base/data/animation/empty_objects.gltf", true, "", "not a readable glTF file: 'sampler' property is missing in AnimationCh"},
    {"base/data/animation/sampler_bufferview_bytestride.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/animation/sampler_input_format_invalid.gltf", true, "animations[0].samplers[0].input", "accessors[0] is SCALAR of UNSIGNED_INT; expected SCALAR of FLOAT"},
    {"base/data/animation/sampler_output_count_invalid.gltf", true, "animations[0].samplers[0].output", "has 2 elements for 1 keys (expected 1)"},
    {"base/data/animation/sampler_output_format_invalid.gltf", true, "animations[0].channels[0].target.path", "accessors[1] is VEC4 of FLOAT; expected VEC3 of FLOAT"},
    {"base/data/animation/sampler_too_few_cubic_frames.gltf", true, "animations[0].samplers[0].input", "CUBICSPLINE needs at least 2 keys, got 1"},
    {"base/data/animation/unresolved_channel_sampler.gltf", true, "animations[0].channels[0].sampler", "sampler 1 does not exist (the file has 1)"},
    {"base/data/animation/unresolved_channel_target.gltf", true, "animations[0].channels[0].target.node", "node 0 does not exist (the file has 0)"},
    {"base/data/animation/unresolved_sampler_input.gltf", true, "animations[0].samplers[0].input", "accessor 1 does not exist (the file has 1)"},
    {"base/data/animation/unresolved_sampler_output.gltf", true, "animations[0].samplers[0].output", "accessor 1 does not exist (the file has 1)"},
    {"base/data/animation_data/invalid_input_values.gltf", true, "animations[0].samplers[0].input", "key time 0 (-1.000000) is negative"},
    {"base/data/animation_data/quaternion_cubic_non_unit_values.gltf", true, "animations[0].samplers[0].input", "key times are not strictly increasing at key 1 (0.000000 after 0.00000"},
    {"base/data/animation_data/quaternion_non_unit_values.gltf", true, "animations[0].samplers[0].input", "key times are not strictly increasing at key 1 (0.000000 after 0.00000"},
    {"base/data/asset/1_0_version.gltf", true, "asset.version", "glTF 1.0 is not supported (only 2.x)"},
    {"base/data/asset/empty_array.gltf", true, "", "not a readable glTF file: \"asset\" object not found in .gltf or not an "},
    {"base/data/asset/invalid_version.gltf", true, "asset.version", "\"1.0.1-dev\" is not a MAJOR.MINOR version"},
    {"base/data/asset/min_version_invalid.gltf", true, "asset.minVersion", "2.1 is greater than the version 2.0"},
    {"base/data/buffer/empty_object.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/buffer/invalid_object.gltf", true, "", "not a readable glTF file: `buffers' does not contain an JSON object."},
    {"base/data/buffer/invalid_uri_data.glb", true, "buffers[0].uri", "data: URI with an unsupported MIME type or encoding (read: base64 with"},
    {"base/data/buffer/invalid_uri_data.gltf", true, "buffers[0].uri", "data: URI with an unsupported MIME type or encoding (read: base64 with"},
    {"base/data/buffer/invalid_uri_data_bytelength.gltf", true, "", "not a readable glTF file: Failed to decode 'uri' : data:application/oc"},
    {"base/data/buffer/invalid_uri_data_mime.gltf", true, "buffers[0].uri", "data: URI with an unsupported MIME type or encoding (read: base64 with"},
    {"base/data/buffer/invalid_uri_scheme.gltf", true, "buffers[0].uri", "URI \":\" has a scheme; only relative paths and data: URIs are read"},
    {"base/data/buffer/no_bin_chunk.glb", true, "buffers[0]", "refers to the GLB's BIN chunk, but the file has none"},
    {"base/data/buffer/not_found.gltf", true, "buffers[0].uri", "\"not_found.bin\" does not exist in the scene's folder"},
    {"base/data/buffer/wrong_bytelength.glb", true, "", "not a readable glTF file: Invalid `byteLength'. Must be equal or less "},
    {"base/data/buffer/zero_bytelength.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/buffer_view/empty_object.gltf", true, "", "not a readable glTF file: 'buffer' property is missing in BufferView."},
    {"base/data/buffer_view/invalid_length.gltf", true, "bufferViews[0]", "byteOffset 0 + byteLength 5 exceeds the 4 bytes of buffers[0]"},
    {"base/data/buffer_view/invalid_stride_multiple.gltf", true, "", "not a readable glTF file: Invalid `byteStride' value. `byteStride' mus"},
    {"base/data/buffer_view/invalid_stride_too_big.gltf", true, "bufferViews[0].byteStride", "4 is larger than the byteLength 1"},
    {"base/data/buffer_view/invalid_stride_wrong_target.gltf", true, "bufferViews[0].byteStride", "index data (target ELEMENT_ARRAY_BUFFER) must be tightly packed"},
    {"base/data/buffer_view/unresolved_buffer.gltf", true, "bufferViews[0].buffer", "buffer 1 does not exist"},
    {"base/data/buffer_view/zero_bytelength.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/camera/empty_objects.gltf", true, "", "not a readable glTF file: 'type' property is missing in `Camera'."},
    {"base/data/camera/infinite_znear.gltf", true, "JSON", "number overflow parsing '1e309'"},
    {"base/data/camera/orthographic_xy.gltf", true, "cameras[0].orthographic.ymag", "must be a finite, non-zero number"},
    {"base/data/camera/orthographic_z.gltf", true, "cameras[0].orthographic.zfar", "must be a finite number > znear (10.000000), got 1.000000"},
    {"base/data/camera/perspective_z.gltf", true, "cameras[0].perspective.zfar", "must be a finite number > znear (10.000000), got 1.000000"},
    {"base/data/glb/chunk_too_big.glb", true, "GLB header", "declared length 13 differs from the file size 48"},
    {"base/data/glb/empty_file.glb", true, "", "the file is empty"},
    {"base/data/glb/empty_json_chunk.glb", true, "GLB chunks[0]", "JSON chunk is empty"},
    {"base/data/glb/empty_json_object.glb", true, "", "not a readable glTF file: \"asset\" object not found in .gltf or not an "},
    {"base/data/glb/invalid_json_chunk.glb", true, "JSON", "parse error at line 1, column 2: syntax error while parsing object key"},
    {"base/data/glb/invalid_magic.glb", true, "GLB header", "magic is not \"glTF\""},
    {"base/data/glb/invalid_version.glb", true, "GLB header", "container version 0 is not supported (only 2)"},
    {"base/data/glb/json_and_two_buffers.glb", true, "GLB chunks[2]", "second BIN chunk (only one is allowed)"},
    {"base/data/glb/length_mismatch.glb", true, "GLB header", "declared length 49 differs from the file size 48"},
    {"base/data/glb/misplaced_bin_chunk.glb", true, "GLB chunks[2]", "BIN chunk must directly follow the JSON chunk"},
    {"base/data/glb/no_header.glb", true, "GLB header", "file is 1 bytes, shorter than the 12-byte GLB header"},
    {"base/data/glb/only_bin_chunk.glb", true, "GLB chunks[0]", "first chunk is \"BIN?\", not the JSON chunk"},
    {"base/data/glb/only_header.glb", true, "GLB header", "no JSON chunk (the file ends after the header)"},
    {"base/data/glb/truncated_chunk_data.glb", true, "GLB header", "declared length 48 differs from the file size 47"},
    {"base/data/glb/truncated_chunk_header.glb", true, "GLB header", "no JSON chunk (the file ends after the header)"},
    {"base/data/glb/two_bin_chunks.glb", true, "GLB chunks[0]", "first chunk is \"BIN?\", not the JSON chunk"},
    {"base/data/glb/two_empty_bin_chunks.glb", true, "GLB chunks[0]", "first chunk is \"BIN?\", not the JSON chunk"},
    {"base/data/glb/two_empty_json_chunks.glb", true, "GLB chunks[0]", "JSON chunk is empty"},
    {"base/data/glb/two_valid_json_chunks.glb", true, "GLB chunks[1]", "second JSON chunk (only one is allowed)"},
    {"base/data/glb/unaligned_chunk.glb", true, "GLB chunks[0]", "chunk length 27 is not a multiple of 4"},
    {"base/data/glb/unknown_chunk.glb", true, "GLB chunks[0]", "first chunk is \"UNKN\", not the JSON chunk"},
    {"base/data/glb/zero_chunk_header.glb", true, "GLB chunks[0]", "first chunk is \"????\", not the JSON chunk"},
    {"base/data/glb/zero_length.glb", true, "GLB header", "declared length 0 differs from the file size 12"},
    {"base/data/image/invalid_data_uri.gltf", true, "", "not a readable glTF file: Failed to decode 'uri' for image[0] name = ["},
    {"base/data/json/empty_file.gltf", true, "", "the file is empty"},
    {"base/data/json/invalid_object.gltf", true, "JSON", "the top level is not a JSON object"},
    {"base/data/json/invalid_syntax.gltf", true, "JSON", "parse error at line 1, column 2: syntax error while parsing object key"},
    {"base/data/material/unresolved_basecolor.gltf", true, "materials[0].pbrMetallicRoughness.baseColorTexture.index", "texture 0 does not exist (the file has 0)"},
    {"base/data/mesh/accessor_unaligned.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/mesh/accessor_unequal_count.gltf", true, "meshes[0].primitives[0].attributes.POSITION", "has 3 elements but COLOR_0 has 4 (attributes of a primitive must match"},
    {"base/data/mesh/accessor_without_bytestride.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/mesh/empty_object.gltf", true, "meshes[3].primitives[0]", "is not an object"},
    {"base/data/mesh/indices_bytestride.gltf", true, "buffers[0]", "has no uri: a .gltf buffer's data must come from a file or a data: URI"},
    {"base/data/mesh/indices_invalid_format.gltf", true, "", "not a readable glTF file: accessor[1] invalid bufferView"},
    {"base/data/mesh/position_accessor_invalid_format.gltf", true, "meshes[0].primitives[0].attributes.POSITION", "accessors[0] is VEC4 of FLOAT; expected VEC3 of FLOAT"},
    {"base/data/mesh/unresolved_indices.gltf", true, "", "not a readable glTF file: primitive indices accessor out of bounds"},
    {"base/data/mesh/unresolved_material.gltf", true, "meshes[0].primitives[0].material", "material 0 does not exist (the file has 0)"},
    {"base/data/mesh/unresolved_positions.gltf", true, "meshes[0].primitives[0].attributes.POSITION", "accessor 0 does not exist (the file has 0)"},
    {"base/data/mesh_data/index_buffer_oob.gltf", true, "meshes[0].primitives[0].indices", "index 5 is out of range (vertex count 4; at position 5)"},
    {"base/data/mesh_data/index_buffer_primitive_restart.gltf", true, "meshes[0].primitives[0].indices", "index 255 (at position 2) is the primitive-restart value of UNSIGNED_B"},
    {"base/data/mesh_data/joints_no_weights.gltf", true, "bufferViews[0]", "byteOffset 0 + byteLength 32 exceeds the 16 bytes of buffers[0]"},
    {"base/data/node/infinite_transform.gltf", true, "JSON", "number overflow parsing '1e309'"},
    {"base/data/node/matrix_indecomposable.gltf", true, "nodes[0].matrix", "last row must be 0, 0, 0, 1 (a projective matrix is not a node transfo"},
    {"base/data/node/node_loop.gltf", true, "nodes[0]", "node hierarchy contains a cycle"},
    {"base/data/node/node_loop_scene.gltf", true, "nodes[0].children[0]", "node is its own child (a cycle)"},
    {"base/data/node/node_parent_override.gltf", true, "nodes[1].children[0]", "node 2 already has parent node 0"},
    {"base/data/node/unresolved_camera.gltf", true, "nodes[0].camera", "camera 0 does not exist (the file has 0)"},
    {"base/data/node/unresolved_child_node.gltf", true, "nodes[0].children[0]", "node 1 does not exist (the file has 1)"},
    {"base/data/skin/unresolved_joint.gltf", true, "skins[0].joints[0]", "node 0 does not exist (the file has 0)"},
    {"base/data/node/unresolved_mesh.gltf", true, "nodes[0].mesh", "mesh 0 does not exist (the file has 0)"},
    {"base/data/root/invalid_array_elements.gltf", true, "", "not a readable glTF file: `materials' does not contain an JSON object."},
    {"base/data/root/undefined_used_extensions.gltf", true, "extensionsRequired[0]", "extension KHR_extension is required by the file but not supported"},
    {"base/data/scene/non_root_node.gltf", true, "scenes[0].nodes[0]", "node 1 is a child of node 0, not a root"},
    {"base/data/scene/unresolved_child_node.gltf", true, "nodes[0].children[0]", "node 5 does not exist (the file has 1)"},
    {"base/data/scene/unresolved_default_scene.gltf", true, "scene", "scene 0 does not exist (the file has 0)"},
    {"base/data/scene/unresolved_node.gltf", true, "scenes[0].nodes[0]", "node 0 does not exist (the file has 0)"},
    {"ext/KHR_lights_punctual/data/light/empty_light_object.gltf", true, "", "not a readable glTF file: 'type' property is missing."},
    {"ext/KHR_lights_punctual/data/light/spot_invalid_angles.gltf", true, "extensions.KHR_lights_punctual.lights[0].spot", "cone angles must satisfy 0 <= innerConeAngle (0.200000) < outerConeAng"},
    {"ext/KHR_lights_punctual/data/light/spot_light_without_spot_object.gltf", true, "", "not a readable glTF file: Spot light description not found."},
    {"ext/KHR_lights_punctual/data/node/empty_object.gltf", true, "nodes[0].extensions.KHR_lights_punctual.light", "is missing or not an integer"},
    {"ext/KHR_lights_punctual/data/node/unresolved_light_empty_root_array.gltf", true, "nodes[0].extensions.KHR_lights_punctual.light", "light 0 does not exist (the file has 0)"},
    {"ext/KHR_lights_punctual/data/node/unresolved_light_empty_root_ext.gltf", true, "nodes[0].extensions.KHR_lights_punctual.light", "light 0 does not exist (the file has 0)"},
    {"ext/KHR_lights_punctual/data/node/unresolved_light_no_root_ext.gltf", true, "nodes[0].extensions.KHR_lights_punctual.light", "light 0 does not exist (the file has 0)"},

    // Loaded, drawing nothing: the file has no scene or no node, which glTF allows; the render
    // command renders the background and says "nothing to draw". The validator's defect in
    // these lies in data no drawn node uses and that Lantern does not read, or is harmless to a
    // renderer: min/max bounds that disagree with the data, colours above 1, non-unit normals,
    // a camera with both projections, a JSON byte-order mark, unused or undecodable images,
    // unknown attributes, skins, empty arrays, misplaced extensions. The same defects in data
    // that is drawn are refused by the loader tests (index, bounds, format, image-decoding
    // cases in tests/unit/Gltf*Test.cpp).
    {"base/data/accessor/byteoffset_no_bufferview.gltf", false, "", kDrawsNothing},
    {"base/data/accessor/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/accessor_data/out_of_range_elements_float.gltf", false, "", kDrawsNothing},
    {"base/data/accessor_data/out_of_range_elements_sint16.gltf", false, "", kDrawsNothing},
    {"base/data/accessor_data/out_of_range_elements_sint8.gltf", false, "", kDrawsNothing},
    {"base/data/accessor_data/out_of_range_elements_uint16.gltf", false, "", kDrawsNothing},
    {"base/data/accessor_data/out_of_range_elements_uint32.gltf", false, "", kDrawsNothing},
    {"base/data/accessor_data/out_of_range_elements_uint8.gltf", false, "", kDrawsNothing},
    {"base/data/animation/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/buffer/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/buffer_view/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/camera/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/camera/extra_type.gltf", false, "", kDrawsNothing},
    {"base/data/glb/bom.glb", false, "", kDrawsNothing},
    {"base/data/image/not_found.gltf", false, "", kDrawsNothing},
    {"base/data/image/png_eos.gltf", false, "", kDrawsNothing},
    {"base/data/json/bom.gltf", false, "", kDrawsNothing},
    {"base/data/material/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/mesh/invalid_attribute.gltf", false, "", kDrawsNothing},
    {"base/data/mesh/position_accessor_no_bounds.gltf", false, "", kDrawsNothing},
    {"base/data/mesh_data/colors_non_clamped.gltf", false, "", kDrawsNothing},
    {"base/data/mesh_data/normals_tangents_non_unit_invalid_sign.gltf", false, "", kDrawsNothing},
    {"base/data/node/empty_array.gltf", false, "", kDrawsNothing},
    {"base/data/root/duplicate_extension_entry.gltf", false, "", kDrawsNothing},
    {"base/data/root/extensions_non_objects.gltf", false, "", kDrawsNothing},
    {"base/data/scene/empty_array.gltf", false, "", kDrawsNothing},
    {"ext/KHR_lights_punctual/data/light/empty_lights_array.gltf", false, "", kDrawsNothing},
    {"ext/KHR_lights_punctual/data/light/empty_object.gltf", false, "", kDrawsNothing},
    {"ext/KHR_materials_unlit/data/material/unexpected_extension.gltf", false, "", kDrawsNothing},

    // Loaded safely: what the validator objects to is skipped or repaired, with a warning.
    {"base/data/animation/channel_duplicate_targets.gltf", false, "", "a second channel animates scale of node 0; the last one wins"},
    {"base/data/animation/channel_node_no_morphs.gltf", false, "", "which draws no morph targets; channel skipped"},
    {"base/data/animation/sampler_input_no_bounds.gltf", false, "", ""},  // min/max are not needed to sample
    {"base/data/mesh_data/joints_weights_complex.gltf", true, "meshes[0].primitives[0].attributes.WEIGHTS_1", "weight -1.000000 of vertex 1 is negative"},  // a POINTS primitive, now read
    {"base/data/node/empty_children_array.gltf", false, "", ""},  // no children is no children
    {"base/data/node/matrix_trs.gltf", false, "", ""},  // the matrix is used (tinygltf drops the TRS unseen)
    {"base/data/node/rotation_non_unit.gltf", false, "", "quaternion length 2.000000 is not 1; normalised"},
    {"base/data/scene/empty_nodes_array.gltf", false, "", ""},  // an empty scene renders empty
    {"base/data/skin/skeleton_invalid.gltf", false, "", "is not an ancestor of joint node 0; the hint is ignored"},
    {"ext/KHR_lights_punctual/data/node/unexpected_extension.gltf", false, "", ""},  // extension where none is read: ignored
};
// clang-format on

} // namespace lantern::test
