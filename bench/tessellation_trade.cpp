// "Model only what a scene requires", measured: spheres8000 as true spheres against the same
// scene with every sphere an icosphere of L subdivisions (tessellated_spheres, 20 x 4^L
// triangles a sphere), shaded smooth (the sphere's normal at each vertex) and flat, through one
// structure: build time, render time, bytes (the structure's and the primitives' own, vertex
// normals included), and the image's error against the render of the true spheres.
//
// Each scene is rendered (Whitted, one thread) `--repetitions` times and the median render time
// is reported, with the smallest and largest. Before timing, the structure's image of the
// sphere scene is checked bit for bit against bvh's (the oracle and image tests hold both equal
// to naive; naive itself would take minutes per image), and so is its image of every triangle
// scene: a mismatch stops the run with status 1. The error is RMSE in radiance units over every
// channel (tracer/image_error.h): flat facets shade and reflect unlike the sphere, and their
// silhouettes lie inside it.
//
//   build/bin/tessellation_trade --out results/tessellation.json [--accel bvh8] [--levels 0,1,2,3]

#include "accel/accel.h"
#include "harness/sweep_machine.h"
#include "scenes_gen/generators.h"
#include "tracer/build_accel.h"
#include "tracer/image_error.h"
#include "tracer/render.h"
#include "tracer/sphere.h"
#include "tracer/triangle.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace {

using nlohmann::json;

struct Options {
  std::string accel = "bvh8";
  std::vector<int> levels = {0, 1, 2, 3};
  int width = 320, height = 240;
  int repetitions = 3;
  std::string out;
};

bool same_image(const tracer::Image& a, const tracer::Image& b) {
  return a.pixels().size() == b.pixels().size() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(tracer::Image::Pixel)) == 0;
}

/// One scene through the structure: its build, its renders, its image.
json measure(const std::string& label, const tracer::Scene& scene, const Options& o, tracer::Image& image) {
  const tracer::Geometry& g = scene.geometry;
  const std::vector<accel::Aabb> boxes = g.primitive_bounds();
  tracer::RenderOptions ro;
  ro.threads = 1;
  ro.width = o.width;
  ro.height = o.height;
  const accel::AnyAccel a = tracer::build_accel(o.accel, nullptr, g, boxes);
  std::vector<double> ms;
  for (int r = 0; r < o.repetitions; ++r) {
    tracer::RenderResult result = tracer::render(scene, a, ro, tracer::whitted_integrator());
    ms.push_back(result.render_ms);
    image = std::move(result.image);
  }
  {
    const accel::AnyAccel check = tracer::build_accel("bvh", nullptr, g, boxes);
    if (!same_image(tracer::render(scene, check, ro, tracer::whitted_integrator()).image, image)) {
      std::fprintf(stderr, "tessellation_trade: %s: %s's image differs from bvh's\n", label.c_str(), o.accel.c_str());
      std::exit(1);
    }
  }
  std::sort(ms.begin(), ms.end());
  const accel::BuildStats& s = accel::stats_of(a);
  const std::uint64_t primitive_bytes = g.spheres.size() * sizeof(tracer::Sphere) +
                                        g.triangles.size() * sizeof(tracer::Triangle) +
                                        g.vertex_normals.size() * sizeof(tracer::Vec3);
  std::fprintf(stderr, "%-8s %9zu primitives  build %8.1f ms  render %8.1f ms  %7.1f MiB\n", label.c_str(),
               std::size_t(g.bounded_count()), s.build_ms, ms[ms.size() / 2],
               double(s.memory_bytes + primitive_bytes) / double(1 << 20));
  return {{"scene", label},
          {"primitives", g.bounded_count()},
          {"triangles", g.triangles.size()},
          {"spheres", g.spheres.size()},
          {"build_ms", s.build_ms},
          {"render_ms", ms[ms.size() / 2]},
          {"render_ms_min", ms.front()},
          {"render_ms_max", ms.back()},
          {"structure_bytes", s.memory_bytes},
          {"primitive_bytes", primitive_bytes}};
}

int run(const Options& o) {
  json rows = json::array();
  tracer::Image spheres_image, image;
  rows.push_back(measure("spheres", scenes_gen::generate("spheres8000", {}), o, spheres_image));
  rows.back()["level"] = nullptr;
  rows.back()["rmse"] = 0.0;
  for (const int level : o.levels) {
    scenes_gen::GenOptions gen;
    gen.count = level;
    tracer::Scene scene = scenes_gen::generate("tessellated_spheres", gen);
    // Smooth (the sphere's normal at each vertex, interpolated), then flat (each facet's own).
    for (const bool smooth : {true, false}) {
      if (!smooth) {
        for (tracer::Triangle& t : scene.geometry.triangles) t.normals = -1;
        scene.geometry.vertex_normals = {};
      }
      const std::string label = "L" + std::to_string(level) + (smooth ? "" : " flat");
      json row = measure(label, scene, o, image);
      const tracer::ImageError e = tracer::image_error(image, spheres_image);
      row["level"] = level;
      row["shading"] = smooth ? "smooth" : "flat";
      row["rmse"] = e.rmse;
      row["mean_bias"] = e.mean_bias;
      std::fprintf(stderr, "         RMSE against the spheres %.4f (mean bias %+.4f)\n", e.rmse, e.mean_bias);
      rows.push_back(std::move(row));
    }
  }
  const json doc = {{"what", "spheres8000 as spheres and as icospheres of L subdivisions (tessellated_spheres), "
                             "shaded smooth and flat"},
                    {"accel", o.accel},
                    {"resolution", {o.width, o.height}},
                    {"threads", 1},
                    {"integrator", "whitted"},
                    {"repetitions", o.repetitions},
                    {"machine", harness::machine_info()},
                    {"rows", rows}};
  if (o.out.empty()) {
    std::printf("%s\n", doc.dump(2).c_str());
  } else {
    std::ofstream f(o.out);
    f << doc.dump(2) << '\n';
    if (!f) {
      std::fprintf(stderr, "tessellation_trade: --out: cannot write '%s'\n", o.out.c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("spheres8000 as spheres against icospheres of L subdivisions: time, bytes and image error");
  app.add_option("--accel", o.accel, "Structure (default bvh8)");
  app.add_option("--levels", o.levels, "Subdivision levels, 0-3")->delimiter(',')->check(CLI::Range(0, 3));
  app.add_option("--width", o.width, "Image width")->check(CLI::Range(1, 8192));
  app.add_option("--height", o.height, "Image height")->check(CLI::Range(1, 8192));
  app.add_option("--repetitions", o.repetitions, "Timed renders per scene (the median is reported)")
      ->check(CLI::Range(1, 100));
  app.add_option("--out", o.out, "JSON file to write (default: standard output)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessellation_trade: %s\n", e.what());
    return 1;
  }
}
