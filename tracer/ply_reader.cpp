#include "ply_reader.h"

#include "scene_error.h"

#include "input/message.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

namespace tracer {

namespace {

bool is_float(PlyType t) { return t == PlyType::Float32 || t == PlyType::Float64; }

/// Reads values one at a time from an ASCII or binary body, never past its end.
class BodyReader {
 public:
  BodyReader(std::string_view bytes, const PlyHeader& h, const std::string& name)
      : bytes_(bytes), pos_(h.body_offset), binary_(h.binary), swap_(h.big_endian), name_(name) {}

  /// Where the next value comes from, for messages.
  void at(const std::string& element, std::uint64_t item) {
    element_ = &element;
    item_ = item;
  }

  double number(PlyType t) { return binary_ ? binary_value(t) : ascii_value(t); }

  /// An integer value (list counts, indices); a float type must hold a whole number.
  std::int64_t integer(PlyType t) {
    const double v = number(t);
    if (!(v == std::floor(v)) || std::abs(v) > 9.0e15) fail("an index or count is not a whole number");
    return std::int64_t(v);
  }

  /// The least bytes `count` values of type t take from here on; throws when they cannot fit.
  void expect(std::uint64_t count, PlyType t) {
    const std::uint64_t each = binary_ ? ply_type_bytes(t) : 2;
    if (count > (bytes_.size() - pos_) / each) fail("a list of " + std::to_string(count) + " values runs past the end of the file");
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw SceneError(name_ + ": element '" + (element_ ? *element_ : std::string("?")) + "' item " +
                     std::to_string(item_) + ": " + why);
  }

  template <class T>
  T raw() {
    if (bytes_.size() - pos_ < sizeof(T)) fail("the file ends early (a truncated binary file?)");
    std::uint8_t b[sizeof(T)];
    std::memcpy(b, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (swap_ == (std::endian::native == std::endian::little))
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

  double binary_value(PlyType t) {
    switch (t) {
      case PlyType::Int8: return raw<std::int8_t>();
      case PlyType::UInt8: return raw<std::uint8_t>();
      case PlyType::Int16: return raw<std::int16_t>();
      case PlyType::UInt16: return raw<std::uint16_t>();
      case PlyType::Int32: return raw<std::int32_t>();
      case PlyType::UInt32: return raw<std::uint32_t>();
      case PlyType::Float32: return raw<float>();
      case PlyType::Float64: return raw<double>();
    }
    return 0.0;
  }

  double ascii_value(PlyType t) {
    while (pos_ < bytes_.size() && (bytes_[pos_] == ' ' || bytes_[pos_] == '\t' || bytes_[pos_] == '\r' || bytes_[pos_] == '\n'))
      ++pos_;
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && bytes_[pos_] != ' ' && bytes_[pos_] != '\t' && bytes_[pos_] != '\r' && bytes_[pos_] != '\n')
      ++pos_;
    if (pos_ == start) fail("the file ends early");
    const char* first = bytes_.data() + start;
    const char* last = bytes_.data() + pos_;
    // Built by appending: GCC 12 misreads `"'" + string` inlined here as an overflow.
    const auto not_a = [&](const char* what) {
      std::string why(1, '\'');
      fail(why.append(input::one_line({first, std::size_t(last - first)}, 40)).append("' is not ").append(what));
    };
    double v = 0.0;
    if (is_float(t)) {
      const auto [end, ec] = std::from_chars(first, last, v);
      if (ec != std::errc() || end != last) not_a("a number");
    } else {
      std::int64_t i = 0;
      const auto [end, ec] = std::from_chars(first, last, i);
      if (ec != std::errc() || end != last) not_a("an integer");
      v = double(i);
    }
    return v;
  }

  std::string_view bytes_;
  std::size_t pos_;
  bool binary_, swap_;
  const std::string& name_;
  const std::string* element_ = nullptr;
  std::uint64_t item_ = 0;
};

}  // namespace

PlyMesh read_ply_body(std::string_view bytes, const PlyHeader& header, const std::string& name) {
  PlyMesh out;
  BodyReader r(bytes, header, name);
  std::vector<std::int64_t> list;
  for (const PlyElement& e : header.elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face", strips = e.name == "tristrips";
    int xyz[3] = {-1, -1, -1};
    if (vertex) {
      for (std::size_t p = 0; p < e.properties.size(); ++p)
        for (int a = 0; a < 3; ++a)
          if (e.properties[p].name == std::string(1, char('x' + a)) && !e.properties[p].list) xyz[a] = int(p);
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
        throw SceneError(name + ": element 'vertex' has no x, y and z properties");
      out.vertices.reserve(out.vertices.size() + e.count);  // e.count is bounded by the file's size
    }
    for (std::uint64_t item = 0; item < e.count; ++item) {
      r.at(e.name, item);
      accel::Vec3 p(0.0f);
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& prop = e.properties[k];
        if (!prop.list) {
          const double v = r.number(prop.type);
          for (int a = 0; a < 3; ++a)
            if (vertex && xyz[a] == int(k)) p[a] = float(v);
          continue;
        }
        const std::int64_t n = r.integer(prop.count_type);
        if (n < 0) throw SceneError(name + ": element '" + e.name + "' item " + std::to_string(item) + ": a list of " + std::to_string(n) + " values");
        r.expect(std::uint64_t(n), prop.type);
        const bool indices = (face || strips) && (prop.name == "vertex_indices" || prop.name == "vertex_index");
        list.clear();
        for (std::int64_t i = 0; i < n; ++i) {
          const std::int64_t v = r.integer(prop.type);
          if (indices) list.push_back(v);
        }
        if (!indices) continue;
        if (face) {
          if (list.size() < 3) ++out.short_faces;
          for (std::size_t i = 2; i < list.size(); ++i) out.triangles.push_back({list[0], list[i - 1], list[i]});
        } else {
          // A strip: each index after the first two makes a triangle with the two before it,
          // every other one flipped; -1 starts a new strip.
          std::size_t run = 0;
          for (std::size_t i = 0; i < list.size(); ++i) {
            if (list[i] == -1) {
              run = 0;
              continue;
            }
            if (++run < 3) continue;
            const std::int64_t a = list[i - 2], b = list[i - 1], c = list[i];
            if ((run & 1) == 1) out.triangles.push_back({a, b, c});
            else out.triangles.push_back({b, a, c});
          }
        }
      }
      if (vertex) out.vertices.push_back(p);
    }
  }
  return out;
}

}  // namespace tracer
