// PlyHeader.h: a PLY file's header (io/mesh/PlyHeader.cpp reads it; PlyLoad.cpp reads the body
// it describes). Only io/mesh/ includes this.
#pragma once

#include "io/mesh/MeshInternal.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::mesh {

enum class PlyType : std::uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };

/// Bytes of a value of `type` in a binary body.
std::size_t plySize(PlyType type);
/// True for the integer types.
inline bool plyInteger(PlyType type) { return type != PlyType::F32 && type != PlyType::F64; }

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::F32;  ///< the value's type (a list's entries)
    bool list = false;
    PlyType countType = PlyType::U8;  ///< a list's length
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    /// The index of property `property`, or -1.
    int find(std::string_view property) const;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t bodyOffset = 0;  ///< the first byte after end_header's line
    std::size_t bodyLine = 1;    ///< its line number (ASCII messages)
};

/// Reads and checks the header: the "ply" magic, a format line, elements and properties of
/// known types, an end_header line (searched for in the bytes, so a file without one is
/// refused at once, never waited on); element counts against what the body's size could
/// hold, before anything is allocated.
Result<PlyHeader> readPlyHeader(const std::vector<unsigned char>& bytes, const Diagnostics& diag);

} // namespace lantern::mesh
