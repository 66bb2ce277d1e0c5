#pragma once
// A PLY file's header, read and checked before the body is handed to a parser: every element
// count is checked against the bytes the file has after its header, so a header that promises
// 10^12 faces, or a binary body that ends early, is refused before anything is allocated.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tracer {

/// The scalar types of PLY properties.
enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

/// One `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`.
struct PlyProperty {
  std::string name;                     ///< "x", "vertex_indices", ...
  bool list = false;                    ///< A list: a count, then that many items.
  PlyType type = PlyType::Float32;      ///< The value's type; a list's item type.
  PlyType count_type = PlyType::UInt8;  ///< A list's count type.
};

/// One `element NAME COUNT` of a PLY header and the least bytes each of its items takes.
struct PlyElement {
  std::string name;               ///< "vertex", "face", "tristrips", ...
  std::vector<PlyProperty> properties;  ///< In file order.
  std::uint64_t count = 0;        ///< Items the header promises.
  std::uint64_t min_item_bytes = 0;  ///< Least bytes of one item (lists empty; ASCII: "0 " per value).
  bool fixed_size = true;         ///< Binary and no list property: every item has exactly that size.
};

struct PlyHeader {
  bool binary = false;              ///< binary_little_endian or binary_big_endian.
  bool big_endian = false;          ///< binary_big_endian.
  std::uint64_t body_offset = 0;    ///< Bytes of the header, "end_header\n" included.
  std::vector<PlyElement> elements;
};

/// Bytes of one value of type t in a binary body.
std::uint64_t ply_type_bytes(PlyType t);

/// Reads and checks the header of the PLY file `bytes`. Throws SceneError "<name>: header line N:
/// ..." on a malformed header, or "<name>: ..." when the body is too short for its counts.
PlyHeader read_ply_header(std::string_view bytes, const std::string& name);

}  // namespace tracer
