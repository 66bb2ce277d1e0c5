#include "harness/sweep_runner.h"

#include "harness/sweep_interrupt.h"
#include "harness/sweep_jsonl.h"
#include "harness/sweep_machine.h"
#include "harness/sweep_measure.h"
#include "harness/sweep_results.h"
#include "harness/sweep_resume.h"
#include "harness/sweep_row.h"
#include "harness/sweep_scene.h"

#include "accel/accel.h"

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <set>

namespace harness {
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

/// A configuration of a batch: its row (nullptr for naive when this shard does not own naive's
/// row, or wrote it with an earlier batch), and what prepare() made of it.
struct Contender {
  const SweepConfig* row = nullptr;  ///< The row to write, or nullptr.
  bool naive = false;                ///< Naive, the reference: contender 0 of every batch.
  Prepared prepared;                 ///< Built, checked, warmed up; then timed.
};

using Emit = std::function<void(json, const SweepConfig&, const std::string&)>;
using Describe = std::function<std::string(const Measurement&, const std::optional<Reference>&)>;

/// Times a batch (contender 0 naive) in interleaved rounds, gives noisy rows more rounds, and
/// writes the rows. Interrupted before its first `repetitions` rounds are complete, it writes
/// only the rows that failed meanwhile: the others are measured again by --resume.
struct TimeBatch {
  const tracer::Scene& scene;
  const SceneSpec& spec;
  std::uint64_t primitives;
  const MeasureOptions& naive_options;  ///< Naive's options (the validation resolution, when set).
  const MeasureOptions& contender_options;  ///< Every other contender's.
  const SweepDefinition& definition;
  RunSummary& summary;
  Emit emit;
  Describe describe;
  bool progress;

  void operator()(std::vector<Contender>& batch) const {
    Rounds rounds(batch.size());
    const auto ok = [&](std::size_t i) { return batch[i].prepared.measurement.status == RowStatus::Ok; };
    const auto time = [&](std::size_t i) {
      return time_render(scene, batch[i].prepared, batch[i].naive ? naive_options : contender_options);
    };
    const bool apart = definition.validates_apart();
    // Runs `count` rounds over naive and `who`; false when stopped before they were complete.
    const auto run_rounds = [&](const std::vector<std::size_t>& who, int count) {
      for (int r = 0; r < count; ++r) {
        std::vector<std::size_t> active;
        for (std::size_t i : who)
          if (ok(i)) active.push_back(i);
        if (!ok(0) || !rounds.run(active, time, [] { return stop_requested(); })) return false;
      }
      return true;
    };
    std::vector<std::size_t> everyone(batch.size());
    for (std::size_t i = 0; i < batch.size(); ++i) everyone[i] = i;
    if (progress)
      std::fprintf(stderr, "sweep: %s: timing %zu configurations and naive in %d interleaved rounds\n",
                   spec.name.c_str(), batch.size() - 1, definition.repetitions);
    const bool complete = run_rounds(everyone, definition.repetitions);

    // Statistics of every contender; the speedup's interval pairs its samples with naive's.
    const auto evaluate = [&]() {
      for (std::size_t i = 0; i < batch.size(); ++i) {
        Measurement& m = batch[i].prepared.measurement;
        if (m.status != RowStatus::Ok) continue;
        set_timings(m, rounds.samples(i));
        double width = m.render_ms_ci->relative_width(m.render_ms->median);
        if (i == 0) {
          m.speedup = 1.0;
          m.speedup_ci = Interval{1.0, 1.0};
        } else if (!apart) {
          const auto [naive_ms, own_ms] = rounds.paired_wall(0, i);
          m.speedup = paired_ratio(naive_ms, own_ms);
          m.speedup_ci = paired_ratio_interval(naive_ms, own_ms);
          width = m.speedup_ci->relative_width(*m.speedup);
        }
        m.noisy = width > definition.noise_threshold;
      }
    };
    if (complete) {
      evaluate();
      // Noisy rows get more rounds (with naive), up to the definition's limit.
      for (int pass = 1; pass <= definition.remeasure && !stop_requested(); ++pass) {
        std::vector<std::size_t> again{0};
        for (std::size_t i = 1; i < batch.size(); ++i)
          if (ok(i) && batch[i].prepared.measurement.noisy) again.push_back(i);
        if (again.size() == 1 && !(batch[0].row && batch[0].prepared.measurement.noisy)) break;
        if (progress)
          std::fprintf(stderr, "sweep: %s: %zu noisy row(s): %d more rounds (pass %d of at most %d)\n",
                       spec.name.c_str(), again.size() - 1 + (batch[0].prepared.measurement.noisy ? 1 : 0), definition.repetitions,
                       pass, definition.remeasure);
        const bool whole = run_rounds(again, definition.repetitions);
        for (std::size_t i : again) batch[i].prepared.measurement.remeasured++;
        evaluate();
        if (!whole) break;
      }
    }
    // Rows: naive's first, then the others in configuration order.
    const Measurement& naive = batch[0].prepared.measurement;
    for (std::size_t i = 0; i < batch.size(); ++i) {
      Contender& c = batch[i];
      if (!c.row) continue;
      // Stopped before the rounds were complete: timed in part, measured again on --resume.
      if (c.prepared.measurement.status == RowStatus::Ok && !complete && naive.status == RowStatus::Ok) continue;
      const MeasureOptions& o = c.naive ? naive_options : contender_options;
      if (c.prepared.measurement.status == RowStatus::Ok && o.inspect && c.prepared.image) inspect(scene, c.prepared, o);
      std::optional<Reference> reference;
      if (naive.status == RowStatus::Ok && complete) {
        // Naive's median over the rounds this row was timed in (every round: naive is in all).
        const auto paired = rounds.paired_wall(0, i);
        reference = Reference{naive.image_hash, paired.first.empty() ? 0.0 : median_of(paired.first), naive.rays, nullptr};
      } else if (c.prepared.measurement.status == RowStatus::Ok) {
        c.prepared.measurement.status = RowStatus::Failed;
        c.prepared.measurement.reason = "naive, the reference, failed while being timed: " + naive.reason;
      }
      emit(make_row(*c.row, spec, primitives, c.naive ? naive_options : contender_options, c.prepared.measurement, reference), *c.row,
           describe(c.prepared.measurement, reference));
    }
    // After the rows: inspecting a row can render too (fronts' references and extra seeds).
    for (Contender& c : batch) {
      summary.trace_s += c.prepared.measurement.spent_trace_s;
      c.prepared.measurement.spent_trace_s = 0.0;  // naive stays for the next batch: count its time once
    }
  }
};

}  // namespace

void set_output_paths(RunOptions& o, const std::string& name, const std::string& out, const std::string& jsonl) {
  o.out_path = out.empty() ? "results/" + name + ".json" : out;
  if (o.shard_count > 1 && out.empty())
    o.out_path = "results/" + name + ".shard" + std::to_string(o.shard_index) + "of" + std::to_string(o.shard_count) + ".json";
  o.jsonl_path = jsonl.empty() ? std::filesystem::path(o.out_path).replace_extension(".jsonl").string() : jsonl;
}

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

  std::vector<SweepConfig> pending;
  for (const auto& c : mine)
    if (!done.count(c.key)) pending.push_back(c);
  summary.already_done = mine.size() - pending.size();
  if (options.progress && summary.already_done)
    std::fprintf(stderr, "sweep: resuming: %zu of %zu configurations already done\n", summary.already_done,
                 mine.size());

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
  if (definition.save_images) {
    // "images": each ok row's image as a PNG named by its hash, beside the JSON Lines file.
    std::filesystem::path dir = options.images_dir;
    if (dir.empty()) {
      const std::filesystem::path jsonl(options.jsonl_path);
      dir = jsonl.parent_path() / (jsonl.stem().string() + "-images");
    }
    mo.inspect = [dir, inner = options.inspect](const tracer::Scene& scene,
                                                const accel::AnyAccel& built,
                                                const MeasureOptions& o, const tracer::Image& image,
                                                Measurement& m) {
      if (inner) inner(scene, built, o, image, m);
      std::filesystem::create_directories(dir);
      const std::string path = (dir / (tracer::hash_hex(image.content_hash()) + ".png")).string();
      image.write_png(path, 0.0f);
      m.extra["image"] = path;
    };
  }
  // Naive, the reference, is rendered at the validation resolution when one is set.
  MeasureOptions naive_mo = mo;
  if (definition.validates_apart()) {
    naive_mo.width = definition.validate_width;
    naive_mo.height = definition.validate_height;
    naive_mo.validate_width = naive_mo.validate_height = 0;
  }

  install_stop_handlers();
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
    if (options.after_row) options.after_row(summary.measured);
  };
  auto describe = [](const Measurement& m, const std::optional<Reference>& reference) {
    if (m.status != RowStatus::Ok || !m.render_ms) return std::string(status_name(m.status)) + ": " + m.reason;
    char buf[256];
    int n = std::snprintf(buf, sizeof buf, "ok, render %.2f ms [%.2f, %.2f], build %.2f ms", m.render_ms->median,
                          m.render_ms_ci->lo, m.render_ms_ci->hi, m.build_ms);
    if (reference && m.speedup && m.speedup_ci)
      n += std::snprintf(buf + n, sizeof buf - std::size_t(n), ", %.2fx naive [%.2f, %.2f]", *m.speedup,
                         m.speedup_ci->lo, m.speedup_ci->hi);
    if (m.noisy) std::snprintf(buf + n, sizeof buf - std::size_t(n), ", noisy");
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

    // One setting of the integrator at a time: naive and every pending configuration with that
    // setting are prepared (built, checked against naive, warmed up), then timed together in
    // interleaved rounds, naive included, so that drift reaches all of them alike.
    std::vector<std::string> settings;                       // in order of first appearance
    std::map<std::string, std::vector<std::size_t>> of_setting;  // setting -> indices into pending
    for (std::size_t i = begin; i < end; ++i) {
      const std::string ip = pending[i].integrator_params.dump();
      if (!of_setting.count(ip)) settings.push_back(ip);
      of_setting[ip].push_back(i);
    }
    for (const std::string& ip : settings) {
      if (stop_requested()) break;
      const std::vector<std::size_t>& members = of_setting[ip];
      const json& integrator_params = pending[members.front()].integrator_params;
      MeasureOptions naive_options = naive_mo, contender_options = mo;
      naive_options.integrator_params = contender_options.integrator_params = integrator_params;
      const std::string naive_key = config_key(spec.name, "naive", json::object(), integrator_params);
      std::optional<std::size_t> naive_row;  // the sweep's own naive row, when it is pending
      for (std::size_t i : members)
        if (pending[i].key == naive_key) naive_row = i;
      naive_options.inspect = naive_row && !definition.validates_apart() ? mo.inspect : nullptr;
      naive_options.keep_image = true;  // the peers' reference (check_against_naive)

      // Contender 0 is naive: the reference for validation, and timed in every round.
      std::vector<Contender> batch;
      batch.push_back({naive_row ? &pending[*naive_row] : nullptr, true,
                       prepare(*scene, boxes, "naive", json::object(), naive_options, std::nullopt)});
      summary.build_s += batch[0].prepared.measurement.spent_build_s;
      if (batch[0].prepared.measurement.status != RowStatus::Ok) {
        summary.trace_s += batch[0].prepared.measurement.spent_trace_s;
        const std::string why = "no naive reference on this scene: " + batch[0].prepared.measurement.reason;
        if (naive_row) emit(make_row(pending[*naive_row], spec, primitives, naive_options, batch[0].prepared.measurement, std::nullopt),
                            pending[*naive_row], describe(batch[0].prepared.measurement, std::nullopt));
        for (std::size_t i : members)
          if (i != naive_row) emit(make_failed_row(pending[i], spec, contender_options, why), pending[i], "failed: " + why);
        continue;
      }
      Reference reference{batch[0].prepared.measurement.image_hash, 0.0, batch[0].prepared.measurement.rays, nullptr};
      if (batch[0].prepared.image) reference.image = std::make_shared<const tracer::Image>(*batch[0].prepared.image);
      const TimeBatch time_batch{*scene, spec, primitives, naive_options, contender_options, definition, summary, emit, describe,
                                 options.progress};
      const std::uint64_t budget = accel::memory_budget_bytes(mo.limits);
      std::uint64_t held = 0;
      for (std::size_t i : members) {
        if (i == naive_row) continue;
        if (stop_requested()) break;
        const SweepConfig& c = pending[i];
        Prepared p = prepare(*scene, boxes, c.structure, c.params, contender_options, reference);
        summary.build_s += p.measurement.spent_build_s;
        if (p.measurement.status != RowStatus::Ok) {
          summary.trace_s += p.measurement.spent_trace_s;
          emit(make_row(c, spec, primitives, contender_options, p.measurement, reference), c, describe(p.measurement, reference));
          continue;
        }
        // Every structure of a batch is held while the rounds run: their memory together stays
        // within the build budget, else the batch is timed and let go before the next one starts.
        const std::uint64_t bytes = p.measurement.build_stats.memory_bytes;
        if (batch.size() > 1 && held + bytes > budget) {
          time_batch(batch);
          batch.resize(1);
          batch[0].row = nullptr;  // naive's row, if any, went out with the first batch
          held = 0;
        }
        batch.push_back({&c, false, std::move(p)});
        held += bytes;
      }
      if (!stop_requested() && (batch.size() > 1 || batch[0].row)) time_batch(batch);
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

}  // namespace harness
