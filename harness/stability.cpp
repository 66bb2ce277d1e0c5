#include "harness/stability.h"

#include "harness/sweep_machine.h"

#include "accel/accel.h"
#include "tracer/build_accel.h"
#include "tracer/image_compare.h"
#include "tracer/intersector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace harness {

namespace {

using nlohmann::json;

const char* kind_name(VariantKind k) {
  switch (k) {
    case VariantKind::Base: return "base";
    case VariantKind::Translate: return "translate";
    case VariantKind::Scale: return "scale";
    case VariantKind::CameraAxis: return "camera_axis";
    case VariantKind::Snapped: return "snapped";
    case VariantKind::Duplicated: return "duplicated";
    case VariantKind::Touching: return "touching";
  }
  return "?";
}

json difference_json(const tracer::ImageDifference& d) {
  return {{"fraction_off", d.fraction_off},
          {"pixels_off", d.pixels_off},
          {"rmse", d.rmse},
          {"max_abs", d.max_abs}};
}

/// Relative change of a count: (v - b) / b; 0 when both are 0, 1 (100%) when only b is.
double change(std::uint64_t v, std::uint64_t b) {
  if (b == 0) return v == 0 ? 0.0 : 1.0;
  return (double(v) - double(b)) / double(b);
}

json ray_change_json(const tracer::RayCounts& v, const tracer::RayCounts& b) {
  return {{"eye_hits", change(v.eye_hits, b.eye_hits)},
          {"reflection", change(v.reflection, b.reflection)},
          {"refraction", change(v.refraction, b.refraction)},
          {"shadow", change(v.shadow, b.shadow)},
          {"total", change(v.total(), b.total())}};
}

/// The label's value: a number when it parses as one, else the string.
json knob_value(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  char* end = nullptr;
  const double d = std::strtod(text.c_str(), &end);
  if (!text.empty() && end == text.c_str() + text.size() && std::isfinite(d)) {
    if (d == std::floor(d) && std::abs(d) < 1e15) return json(std::int64_t(d));
    return json(d);
  }
  return json(text);
}

struct Rendered {
  tracer::RenderResult result;
  std::size_t non_finite = 0;
};

Rendered render_once(const tracer::Scene& scene, const accel::AnyAccel& structure,
                     const StabilityOptions& o, tracer::Precision precision) {
  tracer::RenderOptions ro;
  ro.width = o.width;
  ro.height = o.height;
  ro.threads = o.threads;
  json knobs = o.integrator_params;
  knobs[tracer::kPrecisionKnob] = tracer::precision_name(precision);
  Rendered r;
  r.result = tracer::render(scene, structure, ro, *o.integrator, knobs);
  r.non_finite = tracer::count_non_finite(r.result.image);
  return r;
}

json render_json(const Rendered& r) {
  return {{"rays", r.result.rays},
          {"image_hash", tracer::hash_hex(r.result.image.content_hash())},
          {"non_finite", r.non_finite},
          {"render_ms", r.result.render_ms},
          {"vs_base", nullptr},
          {"ray_change", nullptr}};
}

void write_png(const StabilityOptions& o, const std::string& name, const tracer::Image& image) {
  if (o.images_dir.empty()) return;
  std::filesystem::create_directories(o.images_dir);
  image.write_png((std::filesystem::path(o.images_dir) / (name + ".png")).string());
}

std::string percent(double fraction, int decimals = 2) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, 100.0 * fraction);
  return buf;
}

std::string signed_percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.2f", 100.0 * fraction);
  return buf;
}

}  // namespace

std::vector<CheckedStructure> parse_checked_structures(const std::string& list, const std::string& flag) {
  std::vector<CheckedStructure> out;
  const std::vector<std::string> names = accel::accel_names();
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string entry = list.substr(start, comma - start);
    start = comma + 1;
    if (entry.empty()) continue;
    CheckedStructure s;
    s.label = entry;
    s.params = json::object();
    std::size_t colon = entry.find(':');
    s.name = entry.substr(0, colon);
    if (s.name == "naive")
      throw std::runtime_error(flag + ": naive is the reference every structure is checked against");
    if (std::find(names.begin(), names.end(), s.name) == names.end()) {
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      throw std::runtime_error(flag + ": unknown structure '" + s.name + "' (known: " + known + ")");
    }
    if (!accel::accel_built(s.name))
      throw std::runtime_error(flag + ": structure '" + s.name + "' is not built in this binary");
    while (colon != std::string::npos) {
      const std::size_t next = entry.find(':', colon + 1);
      const std::string knob = entry.substr(colon + 1, next == std::string::npos ? std::string::npos
                                                                                  : next - colon - 1);
      const std::size_t eq = knob.find('=');
      if (eq == std::string::npos || eq == 0)
        throw std::runtime_error(flag + ": '" + entry + "': expected KNOB=VALUE after ':', got '" +
                                 knob + "'");
      s.params[knob.substr(0, eq)] = knob_value(knob.substr(eq + 1));
      colon = next;
    }
    out.push_back(s);
  }
  if (out.empty()) throw std::runtime_error(flag + ": names no structure");
  return out;
}

std::string default_structures() {
  std::string out;
  for (const accel::StructureInfo& info : accel::structures()) {
    const std::string& n = info.name;
    if (n == "naive" || !info.built || !info.exact) continue;  // every structure must equal naive
    out += (out.empty() ? "" : ",") + n;
    // Each other algorithm a variant knob selects (a placement, a split rule) is a structure of
    // its own here: the tables say which they are.
    for (const json& k : info.knob_table)
      if (k.at("variant").get<bool>() && k.contains("choices"))
        for (const json& choice : k.at("choices"))
          if (choice != k.at("default"))
            out += "," + n + ":" + k.at("name").get<std::string>() + "=" + choice.get<std::string>();
  }
  return out;
}

json variant_target(const StabilityVariant& v) {
  const int k = std::abs(v.exponent);
  if (v.kind == VariantKind::Translate) {
    if (k <= 4) return {{"max_ray_change", 0.005}, {"max_fraction_off", 0.01}};
    if (k == 5) return {{"max_ray_change", 0.02}, {"max_fraction_off", 0.05}};
    return {{"max_ray_change", 0.10}, {"max_fraction_off", -1.0}};
  }
  if (v.kind == VariantKind::Scale && k <= 4)
    return {{"max_ray_change", 0.005}, {"max_fraction_off", 0.01}};
  return nullptr;
}

json run_stability(const tracer::Scene& scene, const StabilityOptions& o, std::ostream& progress) {
  if (o.variants.empty() || o.variants.front().kind != VariantKind::Base)
    throw std::invalid_argument("the variants must start with the base scene");
  json doc = {{"kind", "accelbench-stability"},
              {"schema_version", 1},
              {"scene", o.scene_label},
              {"integrator", std::string(o.integrator->name)},
              {"integrator_params", o.integrator_params},
              {"resolution", {o.width, o.height}},
              {"threads", tracer::resolve_threads(o.threads)},
              {"reference", o.reference ? "naive in double" : "none"},
              {"pixel_off_rule",
               "a pixel is off when its largest channel difference exceeds 1% of the brighter "
               "pixel's largest channel (taken as at least 0.01)"},
              {"machine", machine_info()}};
  json labels = json::array();
  for (const CheckedStructure& s : o.structures) labels.push_back(s.label);
  doc["structures"] = labels;

  std::optional<Rendered> base_float, base_double;
  json variants = json::array();
  int failures = 0;
  const std::size_t n = o.variants.size();
  for (std::size_t vi = 0; vi < n; ++vi) {
    const StabilityVariant& v = o.variants[vi];
    const auto started = std::chrono::steady_clock::now();
    progress << "[" << (vi + 1) << "/" << n << "] " << v.name << ":" << std::flush;
    const tracer::Scene scene_v = make_variant(scene, v);
    const std::vector<accel::Aabb> boxes = scene_v.geometry.primitive_bounds();
    const accel::AnyAccel naive = accel::make_accel("naive", json::object(), boxes);

    json row = {{"name", v.name},
                {"group", v.group},
                {"kind", kind_name(v.kind)},
                {"exponent", v.exponent},
                {"direction", {v.direction.x, v.direction.y, v.direction.z}},
                {"same_image", v.same_image},
                {"primitives", scene_v.geometry.bounded_count()},
                {"target", variant_target(v)},
                {"meets_target", nullptr},
                {"double", nullptr},
                {"float_vs_double", nullptr}};
    json row_failures = json::array();

    progress << " naive float" << std::flush;
    Rendered f = render_once(scene_v, naive, o, tracer::Precision::Float);
    write_png(o, v.name + "_float", f.result.image);
    json fj = render_json(f);
    if (f.non_finite > 0)
      row_failures.push_back("float image: " + std::to_string(f.non_finite) + " non-finite pixels");
    if (v.kind == VariantKind::Base) base_float = f;
    if (v.same_image) {
      fj["vs_base"] = difference_json(tracer::compare_images(base_float->result.image, f.result.image));
      fj["ray_change"] = ray_change_json(f.result.rays, base_float->result.rays);
    }

    std::optional<Rendered> d;
    if (o.reference) {
      progress << ", naive double" << std::flush;
      d = render_once(scene_v, naive, o, tracer::Precision::Double);
      write_png(o, v.name + "_double", d->result.image);
      json dj = render_json(*d);
      if (d->non_finite > 0)
        row_failures.push_back("double image: " + std::to_string(d->non_finite) +
                               " non-finite pixels");
      if (v.kind == VariantKind::Base) base_double = d;
      if (v.same_image) {
        dj["vs_base"] =
            difference_json(tracer::compare_images(base_double->result.image, d->result.image));
        dj["ray_change"] = ray_change_json(d->result.rays, base_double->result.rays);
      }
      row["double"] = dj;
      row["float_vs_double"] = difference_json(tracer::compare_images(d->result.image, f.result.image));
    }
    row["float"] = fj;

    json structures = json::array();
    progress << ", " << o.structures.size() << " structures" << std::flush;
    for (const CheckedStructure& s : o.structures) {
      // As render builds it: the triangles' cell test, the wide BVHs' SIMD sphere and triangle leaves.
      accel::AnyAccel built = tracer::build_accel(s.name, s.params, scene_v.geometry, boxes);
      const Rendered r = render_once(scene_v, built, o, tracer::Precision::Float);
      const bool same_image = r.result.image == f.result.image;
      const bool same_rays = r.result.rays == f.result.rays;
      structures.push_back({{"label", s.label},
                            {"name", s.name},
                            {"params", accel::params_of(built)},
                            {"image_hash", tracer::hash_hex(r.result.image.content_hash())},
                            {"rays", r.result.rays},
                            {"equal_image", same_image},
                            {"equal_rays", same_rays}});
      if (!same_image || !same_rays)
        row_failures.push_back(s.label + ": " +
                               (same_image ? "" : "image differs from naive") +
                               (!same_image && !same_rays ? ", " : "") +
                               (same_rays ? "" : "ray counts differ from naive"));
      if (r.non_finite > 0 && same_image == false)
        row_failures.push_back(s.label + ": " + std::to_string(r.non_finite) + " non-finite pixels");
    }
    row["structures"] = structures;

    if (!row["target"].is_null() && !fj["ray_change"].is_null()) {
      const json& t = row["target"];
      const json& c = fj["ray_change"];
      const double max_change = t["max_ray_change"].get<double>();
      bool ok = true;
      for (const char* kind : {"reflection", "refraction", "shadow"})
        ok = ok && std::abs(c[kind].get<double>()) <= max_change;
      const double max_off = t["max_fraction_off"].get<double>();
      if (max_off >= 0.0) ok = ok && fj["vs_base"]["fraction_off"].get<double>() <= max_off;
      row["meets_target"] = ok;
    }
    row["failures"] = row_failures;
    failures += int(row_failures.size());
    variants.push_back(row);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    char tail[64];
    std::snprintf(tail, sizeof tail, " (%.1f s)", seconds);
    progress << tail << (row_failures.empty() ? "" : " FAILED") << "\n";
    for (const auto& msg : row_failures) progress << "    " << msg.get<std::string>() << "\n";
  }
  doc["variants"] = variants;
  doc["failures"] = failures;
  return doc;
}

std::string stability_table(const json& doc) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-20s %8s %9s %8s %8s %8s %8s %9s %9s %8s %7s\n", "variant",
                "px>1%", "rmse", "refl%", "refr%", "shadow%", "hits%", "dbl px>1%", "f-vs-d px",
                "structs", "target");
  out << line;
  for (const json& v : doc["variants"]) {
    const json& f = v["float"];
    std::string px = "-", rmse = "-", refl = "-", refr = "-", shadow = "-", hits = "-";
    if (!f["vs_base"].is_null()) {
      px = percent(f["vs_base"]["fraction_off"].get<double>());
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2e", f["vs_base"]["rmse"].get<double>());
      rmse = buf;
      const json& c = f["ray_change"];
      refl = signed_percent(c["reflection"].get<double>());
      refr = signed_percent(c["refraction"].get<double>());
      shadow = signed_percent(c["shadow"].get<double>());
      hits = signed_percent(c["eye_hits"].get<double>());
    }
    std::string dpx = "-", fvd = "-";
    if (!v["double"].is_null() && !v["double"]["vs_base"].is_null())
      dpx = percent(v["double"]["vs_base"]["fraction_off"].get<double>());
    if (!v["float_vs_double"].is_null()) fvd = percent(v["float_vs_double"]["fraction_off"].get<double>());
    int equal = 0;
    for (const json& s : v["structures"]) equal += s["equal_image"].get<bool>() && s["equal_rays"].get<bool>();
    const std::string structs = std::to_string(equal) + "/" + std::to_string(v["structures"].size());
    const std::string target =
        v["meets_target"].is_null() ? "-" : (v["meets_target"].get<bool>() ? "met" : "MISSED");
    std::snprintf(line, sizeof line, "%-20s %8s %9s %8s %8s %8s %8s %9s %9s %8s %7s\n",
                  v["name"].get<std::string>().c_str(), px.c_str(), rmse.c_str(), refl.c_str(),
                  refr.c_str(), shadow.c_str(), hits.c_str(), dpx.c_str(), fvd.c_str(),
                  structs.c_str(), target.c_str());
    out << line;
  }
  return out.str();
}

}  // namespace harness
