#!/usr/bin/python3
"""Figures from accelbench results files (written by `accelbench sweep` or `accelbench merge`).

Reads only the results JSON files named on the command line and writes, as PNG and SVG:

  paper_speedup   the analogue of the paper's Figures 2 and 3: render time per structure with the
                  speedup over naive on a second axis, for spheres8000 and five, with the paper's
                  own speedups (3.3 octree, 3.8 kd-tree; D. Cohen, "A Better Ray Tracer", RPI) marked;
                  whiskers are the rows' 95% intervals, and a second row of panels shows the
                  machine-independent work per ray (nodes visited, primitives tested)
  heatmap_render_ms, heatmap_nodes_per_ray
                  render time and nodes visited per ray over max_depth x max_leaf_size, per structure
  scaling         render time against the number of spheres (log-log) with fitted slopes and the
                  break-even point against naive, per scene family
  build_vs_trace  build time against render time, and the rays it takes to pay for a build

and prints a Markdown table of the best measured speedups beside the paper's. Results files of
`accelbench fronts` (docs/accuracy.md) give instead, per scene:

  fronts_<scene>  error against median render time for each accuracy knob, the Pareto front
                  highlighted and the reference's own error (its floor) marked (fronts of another
                  integrator than whitted: fronts_<integrator>_<scene>); each point's error
                  interval as an error bar, hollow where it reaches the floor (unresolved)
  convergence_<scene>
                  log-log MSE against photons per map for the photon-count fronts (progressive
                  photon mapping's passes, the photon integrator's global/caustic photons), each
                  with its least-squares slope after the reference's own MSE is subtracted, and
                  the theory's N^-2/3 for progressive photon mapping

Usage: scripts/plot.py results/paper.json results/scaling.json [results/fronts-*.json] [--out results]
"""

import argparse
import itertools
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

CITATION = 'D. Cohen, "A Better Ray Tracer", RPI'
PAPER_SPEEDUP = {"octree": 3.3, "kdtree": 3.8}
PAPER_SCENES = ["spheres8000", "five"]
SCALING_FAMILIES = ["grid", "random", "sphereflake"]
FIGURES = ["paper_speedup", "heatmap_render_ms", "heatmap_nodes_per_ray", "scaling", "build_vs_trace"]

# The structure registry, generated from accel/registry.h by `accelbench structures --json` (a
# test checks it is current): the structures, in display order, and their knobs. Knobs flagged
# "variant" change the algorithm (a split rule, a placement); each of their values is drawn as a
# variant of its own.
REGISTRY_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "structures.json")


def load_registry(path=REGISTRY_FILE):
    """The structures of the registry (selectors such as auto left out), in display order."""
    with open(path, encoding="utf-8") as f:
        return [e for e in json.load(f) if not e.get("selector")]


REGISTRY = load_registry()


def variant_knobs(entry):
    return [k for k in entry["knobs"] if k.get("variant")]


def variant_label(name, values):
    """Display name of a structure with the values of its variant knobs, e.g. 'kdtree (leaves, sah)'."""
    return f"{name} ({', '.join(values)})" if values else name


def variant_order(registry):
    """Every variant of every structure: the cross product of its variant knobs' values."""
    out = []
    for e in registry:
        for values in itertools.product(*[k["choices"] for k in variant_knobs(e)]):
            out.append(variant_label(e["name"], list(values)))
    return out


VARIANT_ORDER = variant_order(REGISTRY)
_PALETTE = plt.get_cmap("tab20").colors
COLORS = {v: _PALETTE[(2 * i) % 20 + (2 * i // 20) % 2] for i, v in enumerate(VARIANT_ORDER)}


class PlotError(Exception):
    """A results file that cannot be plotted; the message is one line."""


def load_rows(paths):
    """Every row of every file, each tagged with its file's resolution and thread count."""
    rows, machines = [], []
    for path in paths:
        try:
            with open(path, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            raise PlotError(f"{path}: cannot read results: {e}") from e
        if not isinstance(doc, dict) or doc.get("format") != "accelbench-results":
            raise PlotError(f"{path}: /format: not an accelbench results file")
        machines.append(doc.get("machine", {}))
        if "mixed_hardware" in doc:  # set by accelbench sweep/merge: rows from different CPUs
            print(f"plot: warning: {path}: {doc['mixed_hardware'].get('warning', 'mixed hardware')}", file=sys.stderr)
        for row in doc.get("rows", []):
            row = dict(row)
            row["_sweep"] = doc.get("sweep", {}).get("name", os.path.basename(path))
            rows.append(row)
    return rows, machines


def variant(row):
    """Display name of a row's structure with the values of the knobs that change its algorithm."""
    params = row.get("params") or row.get("requested") or {}
    name = row.get("built") or row["structure"]
    entry = next((e for e in REGISTRY if e["name"] == name), None)
    if entry is None:
        return name
    return variant_label(name, [str(params.get(k["name"], k["default"])) for k in variant_knobs(entry)])


def paper_structure(row):
    """The paper's structure a row corresponds to: its octree, its midpoint kd-tree, or None."""
    params = row.get("params") or row.get("requested") or {}
    name = row.get("built") or row["structure"]
    if name == "octree":
        return "octree"
    if name == "kdtree" and params.get("split", "midpoint") == "midpoint":
        return "kdtree"
    return None


def order_key(v):
    return VARIANT_ORDER.index(v) if v in VARIANT_ORDER else len(VARIANT_ORDER)


def ok_rows(rows):
    return [r for r in rows if r.get("status") == "ok" and "render_ms" in r]


def best_per_variant(rows, scene):
    """The fastest ok row of each variant on one scene."""
    best = {}
    for r in ok_rows(rows):
        if r["scene"] != scene:
            continue
        v = variant(r)
        if v not in best or r["render_ms"]["median"] < best[v]["render_ms"]["median"]:
            best[v] = r
    return dict(sorted(best.items(), key=lambda kv: order_key(kv[0])))


# Where the figures' numbers were measured, written under every figure (see machine_note).
MACHINE_NOTE = ""


def machine_note(machines):
    """CPU model, the instruction set the build targeted (`machine.isa.build`) and the date, per
    distinct machine of the results; an older file without the field says so."""
    notes = []
    for m in machines:
        if not isinstance(m, dict) or not m:
            continue
        isa = m.get("isa") if isinstance(m.get("isa"), dict) else {}
        level = f"ISA {isa['build']}" if isa.get("build") else "ISA not recorded"
        text = f"{m.get('cpu_model', 'unknown CPU')}, {level}, {str(m.get('date', ''))[:10]}"
        if text not in notes:
            notes.append(text)
    return ("measured on " + "; ".join(notes)) if notes else ""


def save(fig, out_dir, name, note=None):
    """Writes the figure as PNG and SVG with `note` (default: every results file's machines)
    under it."""
    note = MACHINE_NOTE if note is None else note
    if note:
        fig.text(0.99, 0.0, note, ha="right", va="top", fontsize=7, color="0.35")
    paths = []
    for ext in ("png", "svg"):
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, dpi=96 if ext == "png" else None, bbox_inches="tight")
        paths.append(path)
    plt.close(fig)
    for p in paths:
        print(f"plot: wrote {p}")


def setting_text(row):
    threads = row.get("threads", 1)
    return (f"{row.get('width')}x{row.get('height')} pixels, "
            f"{'all cores' if threads == 0 else str(threads) + ' thread' + ('s' if threads != 1 else '')}, "
            + (f"median of {row.get('repetitions')} interleaved rounds (more for noisy rows)" if "remeasured" in row
               else f"median of {row.get('repetitions')}"))


def plot_paper_speedup(rows, out_dir):
    scenes = [s for s in PAPER_SCENES if best_per_variant(rows, s)]
    if not scenes:
        return False
    fig, all_axes = plt.subplots(2, len(scenes), figsize=(7.0 * len(scenes), 9.6), squeeze=False,
                                 gridspec_kw={"height_ratios": [5.6, 2.6]})
    fig.subplots_adjust(wspace=0.42, hspace=0.75, bottom=0.17, top=0.9)
    handles = {}
    for ax, work_ax, scene in zip(all_axes[0], all_axes[1], scenes):
        best = best_per_variant(rows, scene)
        names = list(best)
        x = np.arange(len(names))
        med = np.array([best[n]["render_ms"]["median"] for n in names])
        # Whiskers: the 95% interval of the median where the rows have one, else min to max.
        lo = med - np.array([interval(best[n], "render_ms_ci", best[n]["render_ms"]["min"])[0] for n in names])
        hi = np.array([interval(best[n], "render_ms_ci", best[n]["render_ms"]["max"])[1] for n in names]) - med
        bars = ax.bar(x, med, color=[COLORS.get(n, "grey") for n in names], yerr=[lo, hi], capsize=3,
                      error_kw={"elinewidth": 1, "ecolor": "dimgrey"})
        whiskers = "95% interval of the median" if "render_ms_ci" in best[names[0]] else "min to max"
        handles[f"render time, median (bars; whiskers: {whiskers})"] = bars[0]
        ax.set_yscale("log")
        ax.set_ylim(med.min() / 4, (med + hi).max() * 3)
        ax.set_ylabel("render time (ms, log scale)")
        ax.set_xticks(x)
        ax.set_xticklabels(names, rotation=30, ha="right")
        prims = next(iter(best.values())).get("primitives", "?")
        ax.set_title(f"{scene} ({prims} spheres)")

        ax2 = ax.twinx()
        speed = np.array([best[n].get("speedup", np.nan) for n in names])
        s_lo = speed - np.array([interval(best[n], "speedup_ci", best[n].get("speedup", np.nan))[0] for n in names])
        s_hi = np.array([interval(best[n], "speedup_ci", best[n].get("speedup", np.nan))[1] for n in names]) - speed
        dots = ax2.errorbar(x, speed, yerr=[s_lo, s_hi], fmt="D", color="black", markersize=7, capsize=4,
                            elinewidth=1.5)
        handles["speedup over naive, measured here (right axis; whiskers: 95% interval, paired rounds)"] = dots
        for xi, sp, n in zip(x, speed, names):
            # "noisy" on a line of its own (side by side, neighbours' labels overlapped), on a pale
            # box so that a red label stays legible over the red bar.
            mark = "\nnoisy" if best[n].get("noisy") else ""
            ax2.annotate(f"{sp:.3g}x{mark}", (xi, sp), textcoords="offset points", xytext=(0, 8), ha="center",
                         fontsize=8, fontweight="bold", color="red" if mark else "black",
                         bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8))
        plot_work_per_ray(work_ax, best, names, x)
        # The paper's speedups (spheres8000) at the structures they were measured for, the value
        # written once per structure.
        written = set()
        for xi, n in zip(x, names):
            base = paper_structure(best[n])
            if base and scene == "spheres8000":
                (star,) = ax2.plot([xi], [PAPER_SPEEDUP[base]], "*", color="magenta", markersize=15,
                                   markeredgecolor="black")
                if base not in written:
                    ax2.annotate(f"paper: {PAPER_SPEEDUP[base]}x", (xi, PAPER_SPEEDUP[base]),
                                 textcoords="offset points", xytext=(0, -16), ha="center", fontsize=8,
                                 color="magenta", fontweight="bold")
                    written.add(base)
                handles["the paper's speedup (3.3 octree, 3.8 kd-tree)"] = star
        line = ax2.axhline(1.0, color="grey", linestyle=":", linewidth=1)
        handles["speedup 1: as fast as naive"] = line
        if scene == "five":
            ax2.text(0.02, 0.97, "paper: octree and kd-tree slower than naive here (speedup < 1)",
                     transform=ax2.transAxes, fontsize=8, color="magenta", va="top")
        ax2.set_yscale("log")
        ax2.set_ylabel("speedup over naive (x, log scale)")
        finite = speed[np.isfinite(speed)]
        top = max(np.max(finite) if finite.size else 1.0, 4.0)
        bottom = min(np.min(finite) if finite.size else 1.0, 0.5)
        ax2.set_ylim(bottom / 3, top * 4)
    sample = next(iter(best_per_variant(rows, scenes[0]).values()))
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=2, fontsize=9,
               frameon=False)
    fig.suptitle("Render time per structure (best configuration of each) and speedup over naive; below, the\n"
                 "machine-independent work per ray behind the times (it does not drift with the machine's load)\n"
                 f"analogue of the paper's Figs. 2 and 3 ({CITATION}); {setting_text(sample)}", fontsize=11)
    save(fig, out_dir, "paper_speedup")
    return True


def interval(row, key, fallback):
    """A row's [lo, hi] interval `key`, or [fallback, fallback] in files written before intervals."""
    value = row.get(key)
    if isinstance(value, list) and len(value) == 2:
        return value
    return [fallback, fallback]


def plot_work_per_ray(ax, best, names, x):
    """Nodes visited and primitives tested per ray (the counting pass) for the same configurations."""
    width = 0.38
    nodes = np.array([best[n].get("traversal", {}).get("nodes_per_ray", np.nan) for n in names], dtype=float)
    prims = np.array([best[n].get("traversal", {}).get("prims_per_ray", np.nan) for n in names], dtype=float)
    ax.bar(x - width / 2, np.where(nodes > 0, nodes, np.nan), width, color="#4477aa", label="nodes visited per ray")
    ax.bar(x + width / 2, np.where(prims > 0, prims, np.nan), width, color="#ee8866", label="primitives tested per ray")
    for xi, v in zip(x - width / 2, nodes):
        if v > 0:
            ax.text(xi, v * 1.15, f"{v:.3g}", ha="center", va="bottom", fontsize=7)
    for xi, v in zip(x + width / 2, prims):
        if v > 0:
            ax.text(xi, v * 1.15, f"{v:.3g}", ha="center", va="bottom", fontsize=7)
    positive = [v for v in np.concatenate([nodes, prims]) if v > 0]
    ax.set_yscale("log")
    if positive:
        ax.set_ylim(min(positive) / 3, max(positive) * 8)
    ax.set_xticks(x)
    ax.set_xticklabels(names, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("work per ray (log scale)")
    ax.set_title("work per ray (counting pass)", fontsize=9)
    ax.legend(fontsize=7, loc="upper right", ncol=2)
    ax.grid(True, axis="y", alpha=0.3)


def grid_panel(row):
    """A heat map panel's name: the row's variant, with any other knob the sweep crossed with the
    grid (e.g. kdtree's split_candidates), so that rows differing in it never share a cell."""
    name = row.get("built") or row["structure"]
    entry = next((e for e in REGISTRY if e["name"] == name), None)
    variant_names = {k["name"] for k in variant_knobs(entry)} if entry else set()
    extra = [f"{k}={v}" for k, v in sorted(row.get("requested", {}).items())
             if k not in ("max_depth", "max_leaf_size") and k not in variant_names]
    label = variant(row)
    if not extra:
        return label
    return label[:-1] + ", " + ", ".join(extra) + ")" if label.endswith(")") else f"{label} ({', '.join(extra)})"


def knob_grid_rows(rows):
    """scene -> panel (grid_panel) -> rows that have both max_depth and max_leaf_size requested."""
    grid = {}
    for r in rows:
        req = r.get("requested", {})
        if "max_depth" in req and "max_leaf_size" in req:
            grid.setdefault(r["scene"], {}).setdefault(grid_panel(r), []).append(r)
    return grid


def heatmap_scene(grid):
    """The scene with the most swept configurations, preferring spheres8000."""
    if "spheres8000" in grid:
        return "spheres8000"
    return max(grid, key=lambda s: sum(len(v) for v in grid[s].values()))


def plot_heatmaps(rows, out_dir):
    grid = knob_grid_rows(rows)
    if not grid:
        return False
    scene = heatmap_scene(grid)
    variants = sorted(grid[scene], key=lambda p: (order_key(variant(grid[scene][p][0])), p))
    metrics = [("heatmap_render_ms", "render time (ms)", lambda r: r["render_ms"]["median"]),
               ("heatmap_nodes_per_ray", "nodes visited per ray", lambda r: r["traversal"]["nodes_per_ray"])]
    for name, label, value in metrics:
        cols = min(3, len(variants))
        nrows = math.ceil(len(variants) / cols)
        fig, axes = plt.subplots(nrows, cols, figsize=(max(10.0, 5.0 * cols), 4.2 * nrows + 1.0), squeeze=False)
        fig.subplots_adjust(top=1.0 - 1.0 / (4.2 * nrows + 1.0), hspace=0.35, wspace=0.3)
        cells = [value(r) for v in variants for r in grid[scene][v] if r.get("status") == "ok"]
        positive = [c for c in cells if c > 0]
        norm = LogNorm(vmin=min(positive), vmax=max(positive)) if positive else None
        image = None
        for ax, v in zip(axes.flat, variants):
            vrows = grid[scene][v]
            depths = sorted({r["requested"]["max_depth"] for r in vrows})
            leaves = sorted({r["requested"]["max_leaf_size"] for r in vrows})
            m = np.full((len(depths), len(leaves)), np.nan)
            failed = []
            for r in vrows:
                i, j = depths.index(r["requested"]["max_depth"]), leaves.index(r["requested"]["max_leaf_size"])
                if r.get("status") == "ok":
                    m[i, j] = value(r)
                else:
                    failed.append((i, j, r.get("status", "?")))
            image = ax.imshow(np.ma.masked_invalid(m), origin="lower", cmap="viridis_r", norm=norm,
                              aspect="auto")
            spread = {}  # (i, j) -> half-width of the 95% interval of the median, % of it
            for r in vrows:
                ci = r.get("render_ms_ci")
                if name == "heatmap_render_ms" and r.get("status") == "ok" and isinstance(ci, list):
                    i, j = depths.index(r["requested"]["max_depth"]), leaves.index(r["requested"]["max_leaf_size"])
                    spread[(i, j)] = (100.0 * (ci[1] - ci[0]) / 2.0 / r["render_ms"]["median"], r.get("noisy", False))
            for i in range(len(depths)):
                for j in range(len(leaves)):
                    if np.isfinite(m[i, j]):
                        text = f"{m[i, j]:.3g}"
                        if (i, j) in spread:
                            text += f"\n±{spread[(i, j)][0]:.0f}%" + ("*" if spread[(i, j)][1] else "")
                        ax.text(j, i, text, ha="center", va="center", fontsize=7 if "\n" not in text else 6,
                                color="white" if norm and norm(m[i, j]) > 0.6 else "black")
            for i, j, status in failed:
                ax.text(j, i, status, ha="center", va="center", fontsize=7, color="red")
            if np.isfinite(m).any():
                bi, bj = np.unravel_index(np.nanargmin(m), m.shape)
                ax.add_patch(plt.Rectangle((bj - 0.5, bi - 0.5), 1, 1, fill=False, edgecolor="red", linewidth=2))
            ax.set_xticks(range(len(leaves)))
            ax.set_xticklabels(leaves)
            ax.set_yticks(range(len(depths)))
            ax.set_yticklabels(depths)
            ax.set_xlabel("max_leaf_size (primitives)")
            ax.set_ylabel("max_depth (levels)")
            ax.set_title(v)
        for ax in list(axes.flat)[len(variants):]:
            ax.axis("off")
        if image is not None:
            bar = fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.85, label=f"{label}, log colour scale")
            bar.formatter = matplotlib.ticker.FormatStrFormatter("%.3g")
            bar.minorformatter = matplotlib.ticker.FormatStrFormatter("%.3g")
            bar.update_ticks()
        sample = grid[scene][variants[0]][0]
        note = ("; under each time: half-width of its 95% interval (*: noisy)"
                if name == "heatmap_render_ms" and any("render_ms_ci" in r for v in variants for r in grid[scene][v])
                else "")
        fig.suptitle(f"{label[0].upper() + label[1:]} over max_depth x max_leaf_size on {scene}\n"
                     f"{setting_text(sample)}; red box: the minimum; red text: failed or error{note}", fontsize=11)
        save(fig, out_dir, name)
    return True


def crossing(ns, t_struct, t_naive):
    """Smallest N (log-interpolated) from which the structure is faster than naive: None when it
    never is, 0 when it already is at the smallest N measured."""
    ratio = [math.log(s / n) for s, n in zip(t_struct, t_naive)]
    for k in range(len(ns)):
        if ratio[k] < 0:
            if k == 0:
                return 0
            r0, r1 = ratio[k - 1], ratio[k]
            f = r0 / (r0 - r1)
            return math.exp(math.log(ns[k - 1]) + f * (math.log(ns[k]) - math.log(ns[k - 1])))
    return None


def plot_scaling(rows, out_dir):
    families = [f for f in SCALING_FAMILIES if any(r.get("scene_family") == f for r in ok_rows(rows))]
    if not families:
        return False
    fig, axes = plt.subplots(1, len(families), figsize=(6.0 * len(families), 5.0), squeeze=False)
    for ax, family in zip(axes[0], families):
        scenes = sorted({r["scene"] for r in ok_rows(rows) if r.get("scene_family") == family},
                        key=lambda s: next(r["primitives"] for r in rows if r["scene"] == s and "primitives" in r))
        series = {}
        for s in scenes:
            for v, r in best_per_variant(rows, s).items():
                ci = interval(r, "render_ms_ci", r["render_ms"]["median"])
                series.setdefault(v, []).append((r["primitives"], r["render_ms"]["median"], ci[0], ci[1]))
        naive = {p[0]: p[1] for p in series.get("naive", [])}
        for v in sorted(series, key=order_key):
            pts = sorted(series[v])
            ns = np.array([p[0] for p in pts], dtype=float)
            ts = np.array([p[1] for p in pts])
            t_lo = np.array([p[2] for p in pts])
            t_hi = np.array([p[3] for p in pts])
            keep = ns >= 1
            ns, ts, t_lo, t_hi = ns[keep], ts[keep], t_lo[keep], t_hi[keep]
            if len(ns) == 0:
                continue
            label = v
            # The slope of the large-N end, where the asymptotic cost shows: a least-squares fit
            # over N >= 100, or over N >= 10 when fewer than three points are that large.
            fit = ns >= 100
            if fit.sum() < 3:
                fit = ns >= 10
            if fit.sum() >= 2:
                slope = np.polyfit(np.log10(ns[fit]), np.log10(ts[fit]), 1)[0]
                label += f": slope {slope:.2f}"
            if v != "naive" and naive:
                common = [(n, t) for n, t in zip(ns, ts) if n in naive]
                if len(common) >= 1:
                    be = crossing([c[0] for c in common], [c[1] for c in common], [naive[c[0]] for c in common])
                    if be is None:
                        label += ", never beats naive"
                    elif be == 0:
                        label += f", beats naive at every N (from {ns[0]:.3g})"
                    else:
                        label += f", beats naive from N~{be:.3g}"
                        ax.plot([be], [np.interp(math.log(be), np.log(ns), ts)], "o", mfc="none",
                                color=COLORS.get(v, "grey"), markersize=11)
            ax.errorbar(ns, ts, yerr=[ts - t_lo, t_hi - ts], fmt="-o", color=COLORS.get(v, "grey"), label=label,
                        markersize=4, capsize=2, elinewidth=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("spheres in the scene, N (log scale)")
        ax.set_ylabel("render time (ms, log scale)")
        ax.set_title(f"{family}")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", title="slope: d log t / d log N at large N; "
                  "circle: break-even; whiskers: 95% interval", title_fontsize=7)
    sample = ok_rows([r for r in rows if r.get("scene_family") in families])[0]
    fig.suptitle(f"Render time against scene size (best configuration per N; {setting_text(sample)})",
                 fontsize=11)
    save(fig, out_dir, "scaling")
    return True


def plot_build_vs_trace(rows, out_dir):
    scenes = [s for s in PAPER_SCENES if best_per_variant(rows, s)]
    if not scenes:
        scenes = sorted({r["scene"] for r in ok_rows(rows)})[:2]
    if not scenes:
        return False
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.6))
    fig.subplots_adjust(wspace=0.3)
    main = scenes[0]
    seen = set()
    for r in sorted(ok_rows(rows), key=lambda r: order_key(variant(r))):
        if r["scene"] != main or r["structure"] == "naive":
            continue
        v = variant(r)
        ax.plot(r["build_ms"], r["render_ms"]["median"], "o", color=COLORS.get(v, "grey"), alpha=0.75,
                markersize=5, label=None if v in seen else v)
        seen.add(v)
    # Naive's line only where it rendered what the others did: a sweep with a validation
    # resolution times naive there alone (its time per ray still serves the right panel).
    main_size = next(((r.get("width"), r.get("height")) for r in ok_rows(rows)
                      if r["scene"] == main and r["structure"] != "naive"), None)
    naive_ms = next((r["render_ms"]["median"] for r in ok_rows(rows)
                     if r["scene"] == main and r["structure"] == "naive"
                     and (r.get("width"), r.get("height")) == main_size), None)
    if naive_ms:
        ax.axhline(naive_ms, color=COLORS["naive"], linestyle="--", label="naive render time")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("build time (ms, log scale)")
    ax.set_ylabel("render time (ms, log scale)")
    ax.set_title(f"Every configuration on {main}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)

    # Rays needed before build + n * t_ray(structure) < n * t_ray(naive).
    width = 0.8 / max(1, len(scenes))
    all_variants = sorted({v for s in scenes for v in best_per_variant(rows, s) if v != "naive"}, key=order_key)
    x = np.arange(len(all_variants))
    top = 1.0
    for k, s in enumerate(scenes):
        best = best_per_variant(rows, s)
        if "naive" not in best:
            continue
        naive = best["naive"]
        naive_per_ray = naive["render_ms"]["median"] / max(1, naive["rays"]["total"])
        heights, notes = [], []
        for v in all_variants:
            r = best.get(v)
            if r is None:
                heights.append(np.nan)
                notes.append("")
                continue
            per_ray = r["render_ms"]["median"] / max(1, r["rays"]["total"])
            gain = naive_per_ray - per_ray
            if gain <= 0:
                heights.append(np.nan)
                notes.append("never")
            else:
                heights.append(max(r["build_ms"] / gain, 1.0))
                notes.append("")
        xs = x - 0.4 + width * (k + 0.5)
        bx.bar(xs, heights, width, label=f"{s} (best configuration)", color=["#4477aa", "#ee8866", "#44aa99"][k % 3])
        finite = [h for h in heights if np.isfinite(h)]
        top = max([top] + finite)
        for xi, h, note in zip(xs, heights, notes):
            if note:
                bx.text(xi, 1.2, note, rotation=90, ha="center", va="bottom", fontsize=8, color="red")
            elif np.isfinite(h):
                bx.text(xi, h * 1.1, f"{h:.2g}", ha="center", va="bottom", fontsize=7)
    bx.set_yscale("log")
    bx.set_ylim(1, top * 20)
    bx.set_xticks(x)
    bx.set_xticklabels(all_variants, rotation=30, ha="right")
    bx.set_ylabel("rays traced before the build pays off (log scale)")
    bx.set_title("Rays needed to pay for the build\n= build time / (naive's time per ray - its time per ray)")
    bx.legend(fontsize=8)
    bx.grid(True, axis="y", alpha=0.3)
    fig.suptitle("Build time against trace time (\"never\": not faster than naive on that scene)", fontsize=11)
    save(fig, out_dir, "build_vs_trace")
    return True


def speedup_table(rows):
    """Markdown: best measured speedup per structure beside the paper's."""
    lines = ["| scene | structure | best configuration | render ms | speedup over naive [95% interval] | paper |",
             "| --- | --- | --- | ---: | ---: | ---: |"]
    for scene in PAPER_SCENES:
        for v, r in best_per_variant(rows, scene).items():
            paper = ""
            base = paper_structure(r)
            if scene == "spheres8000" and base:
                paper = str(PAPER_SPEEDUP[base])
            elif scene == "five" and base:
                paper = "< 1"
            knobs = ", ".join(f"{k}={val}" for k, val in sorted(r.get("requested", {}).items())) or "defaults"
            speedup = f"{r.get('speedup', float('nan')):.3g}"
            if isinstance(r.get("speedup_ci"), list) and r["structure"] != "naive":
                speedup += f" [{r['speedup_ci'][0]:.3g}, {r['speedup_ci'][1]:.3g}]"
            lines.append(f"| {scene} | {v} | {knobs} | {r['render_ms']['median']:.3g} | {speedup} | {paper} |")
    return "\n".join(lines)


def is_fronts(doc):
    return isinstance(doc.get("sweep"), dict) and "fronts" in doc["sweep"]


def load_docs(paths):
    """(path, document) of every file, each checked to be a results file."""
    docs = []
    for path in paths:
        try:
            with open(path, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            raise PlotError(f"{path}: cannot read results: {e}") from e
        if not isinstance(doc, dict) or doc.get("format") != "accelbench-results":
            raise PlotError(f"{path}: /format: not an accelbench results file")
        docs.append((path, doc))
    return docs


def knob_label(params, knobs):
    """The values of a row's varied knobs, e.g. "8" or "8, 4"."""
    return ", ".join(f"{params.get(k)}" for k in knobs)


def draw_points(ax, pts, size, color, label, zorder):
    """Front points as markers: filled when the reference resolves their error, hollow (gid
    "unresolved" in the SVG) when their interval reaches the reference's floor."""
    solid = [p for p in pts if p[4]]
    hollow = [p for p in pts if not p[4]]
    ax.scatter([p[0] for p in solid], [p[1] for p in solid], s=size, color=color, label=label if solid else None,
               zorder=zorder)
    if hollow:
        ax.scatter([p[0] for p in hollow], [p[1] for p in hollow], s=size, facecolors="none", edgecolors=color,
                   linewidths=1.2, label=None if solid else label, zorder=zorder, gid="unresolved")


def draw_intervals(ax, pts):
    """Each point's error interval (the seeds' spread widened by the reference's floor) as an
    error bar; a lower end of 0 runs off the bottom of the log axis."""
    with_interval = [p for p in pts if isinstance(p[5], list) and len(p[5]) == 2]
    if not with_interval:
        return
    xs = [p[0] for p in with_interval]
    ys = [p[1] for p in with_interval]
    # null ends are infinite (a broken render): no bar above such a point.
    lo = [y - (p[5][0] if p[5][0] is not None else y) for p, y in zip(with_interval, ys)]
    hi = [(p[5][1] - y) if p[5][1] is not None else 0.0 for p, y in zip(with_interval, ys)]
    ax.errorbar(xs, ys, yerr=[[max(v, 0.0) for v in lo], [max(v, 0.0) for v in hi]], fmt="none", ecolor="0.45",
                elinewidth=0.8, capsize=2, zorder=1, label="error interval (seeds and floor)")


def plot_fronts(doc, out_dir):
    """One figure per scene: error against time for each knob group, the front highlighted."""
    metric = doc["sweep"]["fronts"].get("metric", "rmse")
    eps = doc["sweep"]["fronts"].get("epsilon")
    fronts = doc.get("fronts", [])
    scenes = []
    for f in fronts:
        if f["scene"] not in scenes:
            scenes.append(f["scene"])
    drawn = []
    for scene in scenes:
        mine = [f for f in fronts if f["scene"] == scene]
        cols = min(3, len(mine))
        rows_n = (len(mine) + cols - 1) // cols
        fig, axes = plt.subplots(rows_n, cols, figsize=(4.6 * cols, 3.8 * rows_n), squeeze=False)
        setting = ""
        for ax, front in zip(axes.flat, mine):
            knobs = front["front"].split("*")
            pts, exact = [], []
            for r in ok_rows(doc["rows"]):
                if r.get("scene") != scene or r.get("front") != front["front"]:
                    continue
                err = (r.get("error") or {}).get(metric)
                if err is None:
                    continue
                # Files written before error intervals have neither field: resolved, no interval.
                point = (r["render_ms"]["median"], err, r.get("on_front", False),
                         knob_label(r.get("integrator_params", {}), knobs), r.get("resolved", True),
                         r.get("error_interval"))
                # A configuration equal to the reference (error 0, e.g. double on the precision
                # front) has no place on a log axis: it is drawn below the others, marked.
                (pts if err > 0 else exact).append(point)
                setting = setting_text(r)
            if not pts and not exact:
                ax.set_visible(False)
                continue
            if exact:
                bottom = min([p[1] for p in pts] + [1e-3]) / 10
                ax.scatter([p[0] for p in exact], [bottom] * len(exact), marker="v", s=36, color="tab:red",
                           label="error 0 (equals the reference)", zorder=3)
                for t, _, _, label, _, _ in exact:
                    ax.annotate(label + ": error 0", (t, bottom), textcoords="offset points", xytext=(4, 3),
                                fontsize=7, color="0.25")
            off = [p for p in pts if not p[2]]
            on = sorted((p for p in pts if p[2]), key=lambda p: p[0])
            draw_points(ax, off, 22, "0.6", "dominated", 2)
            draw_points(ax, on, 30, "tab:red", "Pareto front", 3)
            if any(not p[4] for p in pts):
                # One legend entry for every hollow marker, whichever its colour.
                ax.scatter([], [], s=30, facecolors="none", edgecolors="0.3",
                           label="hollow: unresolved (interval reaches the reference floor)")
            draw_intervals(ax, pts)
            if on:
                ax.step([p[0] for p in on], [p[1] for p in on], where="post", color="tab:red", lw=1.2, zorder=2)
            for t, e, _, label, _, _ in pts:
                ax.annotate(label, (t, e), textcoords="offset points", xytext=(4, 3), fontsize=7, color="0.25")
            floor = front.get("floor")
            if floor and floor > 0:
                # How far the front lies above it: the target is 10x (docs/accuracy.md).
                ratio = front.get("floor_ratio")
                label = "reference floor" + (f" (smallest error {ratio:.2g}x it; 10x asked)" if ratio else "")
                stopping = front.get("reference", {}).get("stopping")
                if stopping:
                    label += f"\nreference stopped by {stopping.get('stopped_by', '?')}"
                ax.axhline(floor, color="tab:blue", ls="--", lw=1, label=label)
            ax.set_xscale("log")
            ax.set_yscale("log")
            # Times within a decade get minor labels; short ones, so that they do not collide.
            short = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:.0f}" if v >= 1 else f"{v:.2g}")
            ax.xaxis.set_minor_formatter(short)
            ax.tick_params(axis="x", which="both", labelsize=7)
            ax.set_xlabel("median render time (ms)")
            ax.set_ylabel(metric.upper().replace("_", " ") if metric == "rmse" else f"relative MSE (eps {eps:g})")
            ref = front.get("reference", {})
            made_by = f"{ref.get('integrator', '')} {json.dumps(ref.get('params', {}), separators=(',', ':'))}"
            if ref.get("analytic"):
                made_by = f"the {ref['analytic']}'s closed form (floor 0)"
            ax.set_title(f"{scene}: {' x '.join(knobs)}\nreference {made_by}", fontsize=8)
            ax.grid(True, which="both", alpha=0.25)
            ax.legend(fontsize=7, loc="best")
        for ax in list(axes.flat)[len(mine):]:
            ax.set_visible(False)
        integrator = doc["sweep"].get("integrator", "whitted")
        fig.suptitle(f"Speed/accuracy fronts, {integrator} on {scene} ({setting})", fontsize=10)
        fig.tight_layout()
        # A front comes from one results file: its machine alone.
        save(fig, out_dir, f"fronts_{scene}" if integrator == "whitted" else f"fronts_{integrator}_{scene}",
             machine_note([doc.get("machine", {})]))
        drawn.append(scene)
    return drawn


# Photon-count knobs: (integrator, knob) -> photons per map of a row's integrator_params.
PHOTON_COUNTS = {
    ("ppm", "passes"): lambda p: p.get("passes", 64) * p.get("photons_per_pass", 100000),
    ("photon", "global_photons"): lambda p: p.get("global_photons"),
    ("photon", "caustic_photons"): lambda p: p.get("caustic_photons"),
}


def convergence_series(doc):
    """{scene: [(label, [(N, mse)], floor_mse)]} of a fronts document's photon-count fronts."""
    integrator = doc["sweep"].get("integrator", "whitted")
    out = {}
    for front in doc.get("fronts", []):
        count = PHOTON_COUNTS.get((integrator, front["front"]))
        if count is None:
            continue
        pts = []
        for r in ok_rows(doc["rows"]):
            if r.get("scene") != front["scene"] or r.get("front") != front["front"]:
                continue
            rmse = (r.get("error") or {}).get("rmse")
            n = count(r.get("integrator_params", {}))
            if rmse is not None and rmse > 0 and n:
                pts.append((float(n), rmse * rmse))
        ref = front.get("reference", {})
        floor_rmse = (ref.get("floor") or {}).get("rmse", 0.0) if isinstance(ref.get("floor"), dict) else 0.0
        if not floor_rmse and doc["sweep"]["fronts"].get("metric", "rmse") == "rmse":
            floor_rmse = front.get("floor") or 0.0
        label = f"{integrator} {front['front']}"
        out.setdefault(front["scene"], []).append((label, sorted(pts), floor_rmse * floor_rmse))
    return out


def fit_slope(pts, floor_mse):
    """Least-squares slope of log(MSE - floor) against log N over the points at least 4x above
    the reference's own MSE; None with fewer than three such points."""
    use = [(n, m - floor_mse) for n, m in pts if m > 4.0 * floor_mse]
    if len(use) < 3:
        return None, use
    slope, icpt = np.polyfit(np.log([n for n, _ in use]), np.log([m for _, m in use]), 1)
    return (float(slope), float(icpt)), use


def plot_convergence(docs, out_dir):
    """Log-log MSE against photons per map, per scene, over every photon-count front given."""
    by_scene = {}
    for doc in docs:
        for scene, series in convergence_series(doc).items():
            by_scene.setdefault(scene, []).extend(series)
    drawn = []
    for scene, series in by_scene.items():
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        for i, (label, pts, floor_mse) in enumerate(series):
            if not pts:
                continue
            color = f"C{i}"
            ax.plot([n for n, _ in pts], [m for _, m in pts], "o", color=color, ms=5,
                    label=f"{label} (MSE)")
            fit, use = fit_slope(pts, floor_mse)
            if fit:
                slope, icpt = fit
                xs = np.array([use[0][0], use[-1][0]])
                ax.plot(xs, np.exp(icpt) * xs ** slope + floor_mse, "-", color=color, lw=1.2,
                        label=f"{label}: fitted slope {slope:.3f}")
                print(f"plot: {scene} {label}: MSE slope {slope:.3f} over {len(use)} points "
                      f"(N {use[0][0]:.3g} to {use[-1][0]:.3g}), reference MSE {floor_mse:.3g} subtracted")
                if label.startswith("ppm"):
                    ax.plot(xs, np.exp(icpt) * xs[0] ** slope * (xs / xs[0]) ** (-2.0 / 3.0), ":",
                            color="k", lw=1, label="theory N^-2/3 (Knaus & Zwicker 2011)")
            if floor_mse > 0:
                ax.axhline(floor_mse, color=color, ls="--", lw=0.8, alpha=0.7, label=f"{label}: reference MSE")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("photons per map (all passes)")
        ax.set_ylabel("MSE against the reference")
        ax.set_title(f"Convergence with photon count, {scene}", fontsize=10)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=7, loc="best")
        fig.tight_layout()
        save(fig, out_dir, f"convergence_{scene}")
        drawn.append(scene)
    return drawn


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", nargs="+", help="results JSON files (accelbench sweep/merge output)")
    parser.add_argument("--out", default="results", help="directory for the figures (default: results)")
    args = parser.parse_args(argv)
    try:
        docs = load_docs(args.results)
        sweeps = [p for p, d in docs if not is_fronts(d)]
        rows, machines = load_rows(sweeps)
    except PlotError as e:
        print(f"plot: {e}", file=sys.stderr)
        return 1
    global MACHINE_NOTE
    MACHINE_NOTE = machine_note(machines + [d.get("machine", {}) for _, d in docs if is_fronts(d)])
    fronts_docs = [d for _, d in docs if is_fronts(d)]
    if not ok_rows(rows) and not fronts_docs:
        print("plot: no ok rows to plot", file=sys.stderr)
        return 1
    os.makedirs(args.out, exist_ok=True)
    for doc in fronts_docs:
        if not plot_fronts(doc, args.out):
            print("plot: skipped a fronts file: it holds no fronts", file=sys.stderr)
    plot_convergence(fronts_docs, args.out)
    if not ok_rows(rows):
        return 0
    drawn = {
        "paper_speedup": plot_paper_speedup(rows, args.out),
        "heatmaps": plot_heatmaps(rows, args.out),
        "scaling": plot_scaling(rows, args.out),
        "build_vs_trace": plot_build_vs_trace(rows, args.out),
    }
    for name, ok in drawn.items():
        if not ok:
            print(f"plot: skipped {name}: the results hold no rows for it", file=sys.stderr)
    print(speedup_table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
