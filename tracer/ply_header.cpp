#include "ply_header.h"

#include "scene_error.h"

#include "input/message.h"

#include <charconv>
#include <sstream>

namespace tracer {

namespace {

/// The PLY scalar type called `t`, if it is one.
bool type_of(std::string_view t, PlyType& out) {
  static constexpr std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [name, type] : kNames)
    if (name == t) {
      out = type;
      return true;
    }
  return false;
}

/// A word of the file as a message shows it: printable, at most 40 characters.
std::string shown(std::string_view w) { return input::one_line(w, 40); }

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

}  // namespace

std::uint64_t ply_type_bytes(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

PlyHeader read_ply_header(std::string_view bytes, const std::string& name) {
  // A header longer than this is not a mesh's header.
  constexpr std::size_t kMaxHeaderBytes = 1 << 16;
  PlyHeader h;
  std::size_t pos = 0;
  int line_no = 0;
  bool format_seen = false, ended = false;
  const auto fail = [&](const std::string& why) {
    throw SceneError(name + ": header line " + std::to_string(line_no) + ": " + why);
  };
  while (!ended) {
    const std::size_t nl = bytes.find('\n', pos);
    ++line_no;
    if (nl == std::string_view::npos || nl > kMaxHeaderBytes)
      fail(nl == std::string_view::npos ? "the file ends inside its header (no end_header line)"
                                        : "no end_header in the first 64 KiB");
    const std::string_view line = bytes.substr(pos, nl - pos);
    pos = nl + 1;
    const std::vector<std::string_view> w = words(line);
    if (line_no == 1) {
      if (w.size() != 1 || w[0] != "ply") fail("expected 'ply', the PLY magic word");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() != 3) fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (w[1] == "ascii") h.binary = false;
      else if (w[1] == "binary_little_endian" || w[1] == "binary_big_endian")
        h.binary = true, h.big_endian = w[1] == "binary_big_endian";
      else fail("unknown format '" + shown(w[1]) + "'");
      format_seen = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) fail("expected 'element NAME COUNT'");
      PlyElement e;
      e.name = shown(w[1]);
      const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || end != w[2].data() + w[2].size())
        fail("element '" + e.name + "': count '" + shown(w[2]) + "' is not a whole number in [0, 2^64)");
      h.elements.push_back(e);
    } else if (w[0] == "property") {
      if (h.elements.empty()) fail("a property before any element");
      PlyElement& e = h.elements.back();
      PlyProperty p;
      if (w.size() == 3) {
        if (!type_of(w[1], p.type)) fail("unknown property type '" + shown(w[1]) + "'");
        p.name = shown(w[2]);
        e.min_item_bytes += h.binary ? ply_type_bytes(p.type) : 2;
        e.properties.push_back(p);
      } else if (w.size() == 5 && w[1] == "list") {
        if (!type_of(w[2], p.count_type) || !type_of(w[3], p.type))
          fail("unknown list types '" + shown(w[2]) + " " + shown(w[3]) + "'");
        p.list = true;
        p.name = shown(w[4]);
        e.min_item_bytes += h.binary ? ply_type_bytes(p.count_type) : 2;
        e.fixed_size = false;
        e.properties.push_back(p);
      } else {
        fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
      }
    } else if (w[0] == "end_header") {
      ended = true;
    } else {
      fail("unknown header keyword '" + shown(w[0]) + "'");
    }
  }
  if (!format_seen) throw SceneError(name + ": the header has no format line");
  h.body_offset = pos;
  // Every item takes at least min_item_bytes: counts the body cannot hold are refused here, before
  // a parser reserves memory for them.
  const std::uint64_t body = bytes.size() - pos;
  std::uint64_t need = 0;
  for (PlyElement& e : h.elements) {
    if (!h.binary) e.fixed_size = false;
    if (e.count > 0 && e.min_item_bytes == 0)
      throw SceneError(name + ": element '" + e.name + "' has " + std::to_string(e.count) + " items but no properties");
    const std::uint64_t room = e.min_item_bytes ? (body - std::min(body, need)) / e.min_item_bytes : 0;
    if (e.count > room) {
      std::ostringstream m;
      m << name << ": the header promises " << e.count << " '" << e.name << "' items, which take at least "
        << e.min_item_bytes << " bytes each, but the file has " << body << " bytes after its header"
        << (h.binary ? " (a truncated binary file?)" : "");
      throw SceneError(m.str());
    }
    need += e.count * e.min_item_bytes;
  }
  return h;
}

}  // namespace tracer
