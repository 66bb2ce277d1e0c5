#!/usr/bin/python3
"""Photon-mapping figures from accelbench outputs.

  fig6 RESULTS.json OUT.png   the paper's Figure 6: one labelled panel of the images a sweep with
                              "images": true wrote (sweeps/fig6.json), one per cone_k value
  timings STATS.json... OUT.md
                              the time split of photon renders (render --stats files): photon
                              tracing, map building, and the render loop's thread time in gathers
                              and in direct light, as a Markdown table

Usage: scripts/plot_photon.py fig6 results/fig6.json results/fig6_cone_filter.png
       scripts/plot_photon.py timings build/ring.stats.json ... results/photon_timings.md
"""

import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


class PlotError(Exception):
    """An input that cannot be drawn; the message is one line."""


def fig6(results_path, out_path):
    with open(results_path) as f:
        results = json.load(f)
    rows = [r for r in results.get("rows", []) if r.get("status") == "ok" and "image" in r]
    if not rows:
        raise PlotError(f"{results_path}: no ok rows with an image (sweep key \"images\": true)")
    rows.sort(key=lambda r: float(r["integrator_params"]["cone_k"]))  # the swept knobs
    images = [mpimg.imread(row["image"]) for row in rows]
    cols = 3
    lines = (len(rows) + cols - 1) // cols
    # Each cell: the image at 3.2 in wide, and 0.35 in above it for its title.
    aspect = images[0].shape[0] / images[0].shape[1]
    fig, axes = plt.subplots(lines, cols, figsize=(3.2 * cols, (3.2 * aspect + 0.35) * lines + 0.4),
                             squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, row, image in zip(axes.flat, rows, images):
        p = row["integrator_params"]
        ax.imshow(image)
        ax.set_title(f"cone k = {float(p['cone_k']):g}", fontsize=10)
    p = rows[0]["integrator_stats"]["counting"]["params"]  # every knob used
    fig.suptitle(f"{rows[0]['scene']}: caustic map, cone filter, k = {p['k']} photons, "
                 f"{p['caustic_photons']} caustic photons", fontsize=10)
    fig.tight_layout()
    fig.savefig(out_path, dpi=100)
    print(f"wrote {out_path}")


def timings(stats_paths, out_path):
    lines = ["| render | photon tracing ms | map build ms | render loop ms (wall) | "
             "gathers, thread ms | direct light, thread ms | lookups | photons stored (global / caustic) |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for path in stats_paths:
        with open(path) as f:
            s = json.load(f)
        st = s.get("integrator_stats", {}).get("timed")
        if not st or "timings" not in st:
            raise PlotError(f"{path}: not the --stats file of a photon render")
        t = st["timings"]
        maps = st["maps"]
        stored = " / ".join(str(maps[k].get("stored", "skipped")) for k in ("global", "caustic"))
        name = os.path.basename(path).split(".")[0]
        lines.append(f"| {name} | {t['photon_trace_ms']:.0f} | {t['map_build_ms']:.0f} | "
                     f"{t['render_loop_ms']:.0f} | {t['gather_thread_ms']:.0f} | "
                     f"{t['direct_thread_ms']:.0f} | {st['gather']['lookups']} | {stored} |")
    with open(out_path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {out_path}")


def main(argv):
    try:
        if len(argv) == 3 and argv[0] == "fig6":
            fig6(argv[1], argv[2])
        elif len(argv) >= 3 and argv[0] == "timings":
            timings(argv[1:-1], argv[-1])
        else:
            print(__doc__, file=sys.stderr)
            return 2
    except (OSError, ValueError, KeyError, PlotError) as e:
        print(f"plot_photon: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
