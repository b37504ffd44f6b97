#pragma once
// PLY scalar types by their header names (Stanford's `char`...`double` and the sized aliases
// `int8`...`float64`) and the header, shared by the reader (core/io/mesh/ply_reader.cpp) and the
// model writer that overwrites coordinates in place (core/io/model/mesh_model.cpp).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/binary_cursor.h"

namespace sublift {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

/// The type a header names; false for an unknown name.
inline bool parse_ply_type(std::string_view s, PlyType& t) {
  struct Name {
    std::string_view name;
    PlyType type;
  };
  static constexpr Name kNames[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},     {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},   {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16}, {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},   {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const Name& n : kNames) {
    if (n.name == s) {
      t = n.type;
      return true;
    }
  }
  return false;
}

/// The header name a writer uses for a type (Stanford's: char, uchar, ..., double).
inline std::string_view ply_type_name(PlyType t) {
  static constexpr std::string_view kNames[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
  return kNames[static_cast<int>(t)];
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  std::size_t line = 0;
  std::vector<PlyProperty> props;
};

enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;   // byte offset of the body
  std::size_t lines = 0;  // header lines, end_header included
};

/// Reads and checks the header of a PLY file (the line `ply` to `end_header`); throws InputError
/// naming the line and what is wrong. Defined in core/io/mesh/ply_reader.cpp.
PlyHeader read_ply_header(std::string_view bytes, const std::string& file, std::size_t max_line_length);

/// Bytes of one value in a binary file.
inline std::size_t ply_type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

inline bool ply_type_is_float(PlyType t) { return t == PlyType::Float32 || t == PlyType::Float64; }

/// f(T{}) for the C++ type T that stores a value of type t.
template <class F>
decltype(auto) with_ply_type(PlyType t, F&& f) {
  switch (t) {
    case PlyType::Int8: return f(std::int8_t{});
    case PlyType::UInt8: return f(std::uint8_t{});
    case PlyType::Int16: return f(std::int16_t{});
    case PlyType::UInt16: return f(std::uint16_t{});
    case PlyType::Int32: return f(std::int32_t{});
    case PlyType::UInt32: return f(std::uint32_t{});
    case PlyType::Float32: return f(float{});
    case PlyType::Float64: break;
  }
  return f(double{});
}

/// One binary value of type t as double (integers stay exact); throws InputError naming `what` at EOF.
inline double read_ply_value(BinaryCursor& in, PlyType t, const char* what) {
  return with_ply_type(t, [&](auto x) { return static_cast<double>(in.read<decltype(x)>(what)); });
}

}  // namespace sublift
