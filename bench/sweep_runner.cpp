#include "sweep_runner.h"

#include "sweep_interrupt.h"
#include "sweep_jsonl.h"
#include "sweep_machine.h"
#include "sweep_measure.h"
#include "sweep_results.h"
#include "sweep_resume.h"
#include "sweep_row.h"
#include "sweep_scene.h"

#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>

namespace bench {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::string clock_text(double seconds) {
  const long s = long(seconds + 0.5);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

/// Naive's figures recorded in an earlier row (resume), when that row is usable as a reference.
std::optional<Reference> reference_from_row(const json& row) {
  if (row.value("status", "") != "ok" || !row.contains("render_ms") || !row.contains("image_hash") ||
      !row["image_hash"].is_string() || !row["render_ms"].is_object() || !row["render_ms"].contains("median") ||
      !row["render_ms"]["median"].is_number())
    return std::nullopt;
  Reference r;
  const std::string& hash = row["image_hash"].get_ref<const std::string&>();
  const auto [end, ec] = std::from_chars(hash.data(), hash.data() + hash.size(), r.image_hash, 16);
  if (hash.size() != 16 || ec != std::errc() || end != hash.data() + hash.size()) return std::nullopt;
  r.render_ms = row["render_ms"]["median"].get<double>();
  try {
    if (row.contains("rays")) r.rays = row["rays"].get<tracer::RayCounts>();
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable counts: measure naive again
  }
  return r;
}

/// The test hook: ACCELBENCH_SWEEP_KILL_AFTER_ROWS=N sends this process a signal after N rows,
/// SIGKILL or, with ACCELBENCH_SWEEP_KILL_SIGNAL=TERM, SIGTERM.
std::size_t kill_after_rows() {
  const char* v = std::getenv("ACCELBENCH_SWEEP_KILL_AFTER_ROWS");
  return v ? std::size_t(std::strtoull(v, nullptr, 10)) : 0;
}
int kill_signal() {
  const char* v = std::getenv("ACCELBENCH_SWEEP_KILL_SIGNAL");
  return v && std::string(v) == "TERM" ? SIGTERM : SIGKILL;
}

}  // namespace

RunSummary run_sweep(const SweepDefinition& definition, const RunOptions& options) {
  const auto t_start = Clock::now();
  RunSummary summary;
  const std::vector<SweepConfig> mine = shard(expand(definition), options.shard_index, options.shard_count);
  summary.shard_configs = mine.size();
  const json definition_json = to_json(definition);
  const json shard_json = {{"index", options.shard_index}, {"count", options.shard_count}};

  // Records of earlier runs (--resume), every one checked against this sweep and shard: their
  // rows are done.
  ResumeState state;
  if (options.resume) {
    state = check_resume(read_jsonl(options.jsonl_path), options.jsonl_path, definition, shard_json, mine);
    if (state.torn_tail) {
      std::fprintf(stderr, "sweep: %s: dropping a torn last line (a write cut by a kill)\n", options.jsonl_path.c_str());
      truncate_file(options.jsonl_path, state.valid_bytes);
    }
  }
  const bool fresh = state.records.empty();
  JsonlWriter writer(options.jsonl_path, fresh);
  const json here = machine_info();
  const std::string node = node_name(here);
  json machine;  // the header's: the machine of the first run
  if (fresh) {
    machine = here;
    json header = {{"kind", kHeaderKind}, {"format", "accelbench-sweep-jsonl"}, {"version", kResultsVersion},
                   {"sweep", definition_json}, {"shard", shard_json}, {"machine", machine}};
    writer.append(header);
  } else {
    machine = state.machine;
    writer.append({{"kind", kResumeKind}, {"machine", here}});
  }
  const std::map<std::string, json>& done = state.done;
  // The node that measured a row: its own record, else (rows of older files) the header's.
  auto measured_on = [&](const json& row) {
    return row.contains("node") && row["node"].is_string() ? row["node"].get<std::string>()
                                                           : node_name(machine);
  };

  std::vector<SweepConfig> pending;
  for (const auto& c : mine)
    if (!done.count(c.key)) pending.push_back(c);
  summary.already_done = mine.size() - pending.size();
  if (options.progress && summary.already_done)
    std::fprintf(stderr, "sweep: resuming: %zu of %zu configurations already done\n", summary.already_done,
                 mine.size());
  if (!fresh && node != node_name(machine))
    std::fprintf(
        stderr,
        "sweep: resuming on node %s, started on %s: naive is measured again here for speedups\n",
        node.c_str(), node_name(machine).c_str());

  MeasureOptions mo;
  mo.width = definition.width;
  mo.height = definition.height;
  mo.threads = definition.threads;
  mo.repetitions = definition.repetitions;
  mo.warmup = definition.warmup;
  mo.limits.max_memory_bytes = definition.max_memory_bytes;
  mo.integrator = definition.integrator;
  mo.validate_width = definition.validate_width;
  mo.validate_height = definition.validate_height;
  mo.inspect = options.inspect;
  // Naive, the reference, is rendered at the validation resolution when one is set.
  MeasureOptions naive_mo = mo;
  if (definition.validates_apart()) {
    naive_mo.width = definition.validate_width;
    naive_mo.height = definition.validate_height;
    naive_mo.validate_width = naive_mo.validate_height = 0;
  }

  install_stop_handlers();
  const std::size_t kill_after = kill_after_rows();
  const std::size_t total = pending.size();

  auto emit = [&](json row, const SweepConfig& c, const std::string& what) {
    row["kind"] = kRowKind;
    row["node"] = node;
    writer.append(row);
    summary.measured++;
    if (row.value("status", "") != "ok") summary.not_ok++;
    if (options.progress) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - t_start).count();
      const double left = elapsed / double(summary.measured) * double(total - summary.measured);
      std::string knobs = c.params.dump();
      if (!c.integrator_params.empty()) knobs.append(" ").append(c.integrator_params.dump());
      std::fprintf(stderr, "sweep: [%zu/%zu] %s %s %s: %s | %s elapsed, ~%s left\n", summary.measured, total,
                   definition.scenes[c.scene].name.c_str(), c.structure.c_str(), knobs.c_str(),
                   what.c_str(), clock_text(elapsed).c_str(), clock_text(left).c_str());
    }
    if (kill_after && summary.measured == kill_after) std::raise(kill_signal());
  };
  auto describe = [](const Measurement& m) {
    if (m.status != RowStatus::Ok) return std::string(status_name(m.status)) + ": " + m.reason;
    char buf[160];
    std::snprintf(buf, sizeof buf, "ok, render %.2f ms, build %.2f ms", m.render_ms->median, m.build_ms);
    return std::string(buf);
  };

  // pending is in index order, which is scene-major: measure one scene at a time.
  for (std::size_t begin = 0; begin < pending.size() && !stop_requested();) {
    std::size_t end = begin;
    while (end < pending.size() && pending[end].scene == pending[begin].scene) ++end;
    const SceneSpec& spec = definition.scenes[pending[begin].scene];

    std::optional<tracer::Scene> scene;
    std::string scene_error;
    try {
      scene = load_sweep_scene(spec);
    } catch (const std::exception& e) {
      scene_error = "scene " + spec.name + ": " + e.what();
    }
    if (!scene) {
      for (std::size_t i = begin; i < end && !stop_requested(); ++i)
        emit(make_failed_row(pending[i], spec, mo, scene_error), pending[i], "failed: " + scene_error);
      begin = end;
      continue;
    }
    const std::vector<accel::Aabb> boxes = scene->geometry.primitive_bounds();
    const std::uint64_t primitives = boxes.size();

    // The references: naive on this scene with each integrator setting, from an earlier row
    // measured on this node, this shard's naive row, or a measurement made only for validation
    // and speedups. A speedup is never a ratio of times from two nodes: resumed on another node,
    // naive is measured again.
    struct NaiveReference {
      std::optional<Reference> reference;
      std::string why_not;  // when there is none
    };
    std::map<std::string, NaiveReference> references;  // by integrator params
    std::set<std::size_t> emitted;                      // naive rows written while measuring it
    auto reference_for = [&](const SweepConfig& c) -> const NaiveReference& {
      const std::string ip = c.integrator_params.dump();
      if (const auto it = references.find(ip); it != references.end()) return it->second;
      NaiveReference& r = references[ip];
      const std::string naive_key = config_key(spec.name, "naive", json::object(), c.integrator_params);
      if (const auto it = done.find(naive_key); it != done.end() && measured_on(it->second) == node)
        r.reference = reference_from_row(it->second);
      if (r.reference) return r;
      if (options.progress)
        std::fprintf(stderr, "sweep: %s: measuring naive, the reference%s\n", spec.name.c_str(),
                     c.integrator_params.empty() ? "" : (" for " + c.integrator_params.dump()).c_str());
      // The sweep's own naive row for this setting, if it is pending: this measurement is its
      // row (with the inspector's findings when naive is timed at the timed resolution).
      std::optional<std::size_t> row_index;
      for (std::size_t i = begin; i < end; ++i)
        if (pending[i].key == naive_key && !emitted.count(i)) row_index = i;
      MeasureOptions nmo = naive_mo;
      nmo.integrator_params = c.integrator_params;
      nmo.inspect = row_index && !definition.validates_apart() ? mo.inspect : nullptr;
      const Measurement naive = measure(*scene, boxes, "naive", json::object(), nmo, std::nullopt);
      summary.build_s += naive.spent_build_s;
      summary.trace_s += naive.spent_trace_s;
      if (naive.status == RowStatus::Ok) r.reference = Reference{naive.image_hash, naive.render_ms->median, naive.rays};
      else r.why_not = "no naive reference on this scene: " + naive.reason;
      if (row_index) {
        emit(make_row(pending[*row_index], spec, primitives, nmo, naive, r.reference), pending[*row_index],
             describe(naive));
        emitted.insert(*row_index);
      }
      return r;
    };
    for (std::size_t i = begin; i < end && !stop_requested(); ++i) {
      if (emitted.count(i)) continue;
      const SweepConfig& c = pending[i];
      const NaiveReference& ref = reference_for(c);
      if (emitted.count(i)) continue;  // c was naive itself, written just now
      if (stop_requested()) break;
      MeasureOptions cmo = mo;
      cmo.integrator_params = c.integrator_params;
      if (!ref.reference) {
        emit(make_failed_row(c, spec, cmo, ref.why_not), c, "failed: " + ref.why_not);
        continue;
      }
      const Measurement m = measure(*scene, boxes, c.structure, c.params, cmo, ref.reference);
      summary.build_s += m.spent_build_s;
      summary.trace_s += m.spent_trace_s;
      std::string what = describe(m);
      if (m.status == RowStatus::Ok && m.render_ms && !definition.validates_apart()) {
        char buf[48];
        std::snprintf(buf, sizeof buf, ", %.2fx naive", ref.reference->render_ms / m.render_ms->median);
        what += buf;
      }
      emit(make_row(c, spec, primitives, cmo, m, ref.reference), c, what);
    }
    begin = end;
  }
  summary.interrupted = stop_requested();
  summary.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();

  json run = {{"kind", kRunKind},
              {"finished", utc_now_iso8601()},
              {"rows_written", summary.measured},
              {"interrupted", summary.interrupted},
              {"wall_s", summary.wall_s},
              {"build_s", summary.build_s},
              {"trace_s", summary.trace_s},
              {"harness_s", summary.wall_s - summary.build_s - summary.trace_s},
              {"harness_fraction", summary.harness_fraction()}};
  writer.append(run);
  // The results file is built from what is on disk, so it holds exactly what a resume would see.
  const json results = assemble_results(read_jsonl(options.jsonl_path).records, machine, definition,
                                        options.shard_index, options.shard_count, mine);
  summary.complete = results["complete"].get<bool>();
  if (results.contains("mixed_hardware"))
    summary.hardware_warning = results["mixed_hardware"]["warning"];
  summary.rows = results["rows"].size();
  for (const auto& row : results["rows"]) summary.ok_rows += row.value("status", "") == "ok";
  write_json_atomic(options.out_path, results);
  return summary;
}

}  // namespace bench
