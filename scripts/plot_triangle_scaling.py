#!/usr/bin/python3
"""The triangle scaling figure: build time, camera and incoherent rays per second, and bytes per
triangle against the number of triangles, for every structure and Embree's own triangles, from
bench_trace's Scaling benchmarks (copies of spot in a grid, and spheres8000 tessellated).

    build/bin/bench_trace --benchmark_filter='^Scaling/' --benchmark_out=scaling.json \\
        --benchmark_out_format=json
    scripts/plot_triangle_scaling.py scaling.json [more.json ...] --out results/triangle_scaling

Several files may be given (one run split by filter); a benchmark measured in more than one keeps
the last. Writes OUT.png, OUT.svg and OUT.json (the numbers plotted, with the machine and ISA); a
benchmark that failed its check against naive is left out, named on stderr and in OUT.json.
Exit status 2, with one line, when a file cannot be read or holds no Scaling benchmark.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [("build", "build time (ms)"), ("coherent", "camera rays (Mrays/s)"),
          ("incoherent", "incoherent rays (Mrays/s)"), ("bytes", "bytes per triangle (structure)")]
FAMILIES = {"spots": ("copies of spot", "-", "o"), "tess": ("tessellated spheres8000", "--", "s")}


def fail(message):
    print("plot_triangle_scaling: " + message, file=sys.stderr)
    sys.exit(2)


def read(paths):
    """{(scene, structure): {"triangles", "build", "bytes", "coherent", "incoherent"}}, the context, and
    {benchmark: message} of the benchmarks that failed their check against naive (left out)."""
    rows, context, failed = {}, {}, {}
    for path in paths:
        try:
            with open(path) as f:
                data = json.load(f)
            benchmarks = data["benchmarks"]
        except (OSError, ValueError, KeyError, TypeError) as e:
            fail("%s: cannot read bench_trace's JSON (%s)" % (path, e))
        context = data.get("context", context)
        for b in benchmarks:
            name = b.get("run_name", b.get("name", ""))
            parts = name.split("/")
            if len(parts) != 4 or parts[0] != "Scaling":
                continue
            if b.get("error_occurred"):
                failed[name] = b.get("error_message", "?")
                continue
            if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
                continue
            _, scene, what, structure = parts
            row = rows.setdefault((scene, structure), {})
            if what == "build":
                scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
                row["build"] = b["real_time"] * scale
                row["bytes"] = b.get("bytes_per_prim")
                row["triangles"] = b.get("primitives")
            elif "rays" in b:
                row[what] = b["rays"] / 1e6
    if not rows:
        fail("no Scaling benchmark in %s" % ", ".join(paths))
    return rows, context, failed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("inputs", nargs="+")
    parser.add_argument("--out", default="results/triangle_scaling")
    args = parser.parse_args()
    rows, context, failed = read(args.inputs)
    for name, message in sorted(failed.items()):
        print("plot_triangle_scaling: left out, failed its check: %s: %s" % (name, message), file=sys.stderr)
    # A scene's triangle count comes from its build rows.
    triangles = {}
    for (scene, _), row in rows.items():
        if row.get("triangles"):
            triangles[scene] = row["triangles"]
    structures = sorted({s for _, s in rows})
    colors = {s: plt.cm.tab10(i % 10) for i, s in enumerate(structures)}
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    table = []
    for ax, (key, label) in zip(axes.flat, PANELS):
        for structure in structures:
            for family, (_, style, marker) in FAMILIES.items():
                pts = sorted((triangles[scene], row[key]) for (scene, s), row in rows.items()
                             if s == structure and scene.startswith(family) and scene in triangles
                             and row.get(key) is not None)
                if not pts:
                    continue
                ax.plot([p[0] for p in pts], [p[1] for p in pts], linestyle=style, marker=marker, markersize=4,
                        color=colors[structure], label=structure if family == "spots" else None)
        ax.set_xscale("log")
        if key == "bytes":
            ax.set_ylim(bottom=0)
        else:
            ax.set_yscale("log")
        ax.set_xlabel("triangles")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    for (scene, structure), row in sorted(rows.items(), key=lambda kv: (kv[0][1], triangles.get(kv[0][0], 0))):
        table.append({"scene": scene, "structure": structure, "triangles": triangles.get(scene),
                      "build_ms": row.get("build"), "bytes_per_triangle": row.get("bytes"),
                      "camera_mrays_per_s": row.get("coherent"), "incoherent_mrays_per_s": row.get("incoherent")})
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 6), fontsize=8)
    isa = context.get("isa", "?")
    fig.suptitle("Triangles: one thread, ISA %s; %s CPUs at %s MHz, %s. Solid: copies of spot; dashed: "
                 "tessellated spheres8000" % (isa, context.get("num_cpus", "?"), context.get("mhz_per_cpu", "?"),
                                              str(context.get("date", "?"))[:10]), fontsize=9)
    fig.tight_layout(rect=(0, 0.06, 1, 0.96))
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    fig.savefig(args.out + ".png", dpi=80)
    fig.savefig(args.out + ".svg")
    with open(args.out + ".json", "w") as f:
        json.dump({"context": {k: context.get(k) for k in ("isa", "num_cpus", "mhz_per_cpu", "date", "host_name")},
                   "rows": table, "failed": failed}, f, indent=1)
    print("plot_triangle_scaling: wrote %s.png, %s.svg and %s.json" % (args.out, args.out, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
