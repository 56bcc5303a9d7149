// GltfTestBuilder.h: builds small glTF files for loader tests: typed accessors over one binary
// buffer (embedded as a data: URI, written beside the file, or put in a GLB BIN chunk), and
// the JSON around them, edited freely through nlohmann::json.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace lantern::test {

class GltfBuilder {
public:
    nlohmann::json doc;
    std::vector<unsigned char> bin;
    /// Buffers written after buffer 0 (the binary buffer), as given (meshopt fallback buffers).
    std::vector<nlohmann::json> extraBuffers;

    GltfBuilder() {
        doc["asset"] = {{"version", "2.0"}};
        doc["scene"] = 0;
        doc["scenes"] = nlohmann::json::array({nlohmann::json{{"nodes", nlohmann::json::array()}}});
    }

    /// Appends raw bytes (4-byte aligned) as a new buffer view; returns its index.
    int addView(const void* data, std::size_t bytes, std::size_t stride = 0) {
        while (bin.size() % 4 != 0) bin.push_back(0);
        const std::size_t offset = bin.size();
        bin.insert(bin.end(), static_cast<const unsigned char*>(data),
                   static_cast<const unsigned char*>(data) + bytes);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
        if (stride) view["byteStride"] = stride;
        doc["bufferViews"].push_back(view);
        return int(doc["bufferViews"].size()) - 1;
    }

    /// An accessor of `type` ("VEC3"...) over `values` stored as `componentType`.
    template <typename T>
    int addAccessor(const std::vector<T>& values, const std::string& type, int componentType,
                    bool normalized = false) {
        const int view = addView(values.data(), values.size() * sizeof(T));
        nlohmann::json a = {{"bufferView", view},
                            {"componentType", componentType},
                            {"count", values.size() / components(type)},
                            {"type", type}};
        if (normalized) a["normalized"] = true;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }
    int addFloats(const std::vector<float>& values, const std::string& type) {
        return addAccessor(values, type, 5126);
    }
    int addIndices(const std::vector<std::uint16_t>& values) {
        return addAccessor(values, "SCALAR", 5123);
    }

    /// A mesh with one primitive; returns the mesh index.
    int addMesh(const nlohmann::json& primitive) {
        doc["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
        return int(doc["meshes"].size()) - 1;
    }
    /// A node, listed as a root of scene 0 when `root`; returns its index.
    int addNode(const nlohmann::json& node, bool root = true) {
        doc["nodes"].push_back(node);
        const int index = int(doc["nodes"].size()) - 1;
        if (root) doc["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    /// A triangle in the XY plane with a mesh and a root node (the smallest renderable file).
    int addTriangle(nlohmann::json primitiveExtras = nlohmann::json::object()) {
        nlohmann::json prim = {{"attributes", {{"POSITION", addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3")}}}};
        prim.update(primitiveExtras);
        return addNode({{"mesh", addMesh(prim)}});
    }

    enum class Storage { DataUri, External, Glb };

    /// Writes the file (name without extension) into `dir` and returns its path.
    std::filesystem::path write(const std::filesystem::path& dir, const std::string& name,
                                Storage storage = Storage::DataUri) {
        nlohmann::json out = doc;
        if (!bin.empty()) {
            nlohmann::json buffer = {{"byteLength", bin.size()}};
            if (storage == Storage::DataUri)
                buffer["uri"] = "data:application/octet-stream;base64," + base64(bin);
            if (storage == Storage::External) {
                buffer["uri"] = name + ".bin";
                writeBytes(dir / (name + ".bin"), bin);
            }
            out["buffers"] = nlohmann::json::array({buffer});
        }
        for (const nlohmann::json& extra : extraBuffers) {
            if (!out.contains("buffers")) out["buffers"] = nlohmann::json::array({{{"byteLength", 0}}});
            out["buffers"].push_back(extra);
        }
        if (storage != Storage::Glb) {
            const std::string text = out.dump(1);
            const auto path = dir / (name + ".gltf");
            writeBytes(path, std::vector<unsigned char>(text.begin(), text.end()));
            return path;
        }
        std::string json = out.dump();
        while (json.size() % 4 != 0) json += ' ';
        std::vector<unsigned char> binChunk = bin;
        while (binChunk.size() % 4 != 0) binChunk.push_back(0);
        std::vector<unsigned char> glb;
        auto u32 = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) glb.push_back((v >> (8 * i)) & 0xFF);
        };
        const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + binChunk.size());
        u32(0x46546C67);
        u32(2);
        u32(std::uint32_t(total));
        u32(std::uint32_t(json.size()));
        u32(0x4E4F534A);
        glb.insert(glb.end(), json.begin(), json.end());
        if (!bin.empty()) {
            u32(std::uint32_t(binChunk.size()));
            u32(0x004E4942);
            glb.insert(glb.end(), binChunk.begin(), binChunk.end());
        }
        const auto path = dir / (name + ".glb");
        writeBytes(path, glb);
        return path;
    }

    static void writeBytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
        std::ofstream f(path, std::ios::binary);
        f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }

    static std::string base64(const std::vector<unsigned char>& data) {
        static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        std::size_t i = 0;
        for (; i + 2 < data.size(); i += 3) {
            const std::uint32_t v = std::uint32_t(data[i]) << 16 | std::uint32_t(data[i + 1]) << 8 | data[i + 2];
            for (int k = 3; k >= 0; --k) out += table[(v >> (6 * k)) & 63];
        }
        if (i < data.size()) {
            std::uint32_t v = std::uint32_t(data[i]) << 16;
            if (i + 1 < data.size()) v |= std::uint32_t(data[i + 1]) << 8;
            out += table[(v >> 18) & 63];
            out += table[(v >> 12) & 63];
            out += i + 1 < data.size() ? table[(v >> 6) & 63] : '=';
            out += '=';
        }
        return out;
    }

private:
    static std::size_t components(const std::string& type) {
        if (type == "SCALAR") return 1;
        if (type == "VEC2") return 2;
        if (type == "VEC3") return 3;
        if (type == "VEC4" || type == "MAT2") return 4;
        if (type == "MAT3") return 9;
        return 16;
    }
};

} // namespace lantern::test
