#!/usr/bin/python3
"""The tessellation trade: spheres8000 as true spheres against icospheres of L subdivisions
(bench/tessellation_trade.cpp), as one figure of three panels over L: build and render time,
bytes (structure and primitives), and the image's RMSE against the true spheres.

Usage: scripts/plot_tessellation.py results/tessellation.json results/tessellation_trade.png
       (an .svg beside the .png is written too)
"""

import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


class PlotError(Exception):
    """An input that cannot be drawn; the message is one line."""


def load(path):
    try:
        with open(path) as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        raise PlotError(f"{path}: {e}")
    rows = doc.get("rows")
    if not isinstance(rows, list) or not rows or rows[0].get("scene") != "spheres":
        raise PlotError(f"{path}: expected 'rows' starting with the spheres row (tessellation_trade --out)")
    levels = [r for r in rows[1:] if isinstance(r.get("level"), int)]
    if not levels:
        raise PlotError(f"{path}: no tessellated rows")
    smooth = [r for r in levels if r.get("shading", "smooth") == "smooth"]
    flat = [r for r in levels if r.get("shading") == "flat"]
    return doc, rows[0], smooth, flat


def plot(path, out):
    doc, spheres, smooth, flat = load(path)
    x = [r["level"] for r in smooth]
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.6))
    mib = 1 << 20

    ax = axes[0]
    ax.plot(x, [r["render_ms"] for r in smooth], "o-", color="C0", label="render, triangles (smooth)")
    ax.plot(x, [r["build_ms"] for r in smooth], "s-", color="C1", label="build, triangles")
    ax.axhline(spheres["render_ms"], color="C0", ls="--", label="render, spheres")
    ax.axhline(max(spheres["build_ms"], 1e-3), color="C1", ls=":", label="build, spheres")
    ax.set_yscale("log")
    ax.set_ylabel("ms (one thread)")
    ax.set_title("time")

    ax = axes[1]
    ax.plot(x, [(r["structure_bytes"] + r["primitive_bytes"]) / mib for r in smooth], "o-", color="C2",
            label="triangles, smooth (with normals)")
    if flat:
        ax.plot([r["level"] for r in flat], [(r["structure_bytes"] + r["primitive_bytes"]) / mib for r in flat],
                "o:", color="C2", mfc="none", label="triangles, flat")
    ax.axhline((spheres["structure_bytes"] + spheres["primitive_bytes"]) / mib, color="C2", ls="--", label="spheres")
    ax.set_yscale("log")
    ax.set_ylabel("MiB (structure + primitives)")
    ax.set_title("memory")

    ax = axes[2]
    ax.plot(x, [r["rmse"] for r in smooth], "o-", color="C3", label="smooth shading")
    if flat:
        ax.plot([r["level"] for r in flat], [r["rmse"] for r in flat], "o:", color="C3", mfc="none",
                label="flat shading")
    ax.set_yscale("log")
    ax.set_ylabel("RMSE against the spheres' image")
    ax.set_title("image error")

    for ax in axes:
        ax.set_xlabel("subdivision level L (20 x 4^L triangles a sphere)")
        ax.set_xticks(x)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    w, h = doc.get("resolution", ["?", "?"])
    fig.suptitle(f"spheres8000: 8000 spheres against icospheres, {doc.get('accel')} at {w}x{h}, "
                 f"Whitted, median of {doc.get('repetitions')} renders", fontsize=10)
    m = doc.get("machine") if isinstance(doc.get("machine"), dict) else {}
    isa = m.get("isa") if isinstance(m.get("isa"), dict) else {}
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.text(0.99, 0.01, f"measured on {m.get('cpu_model', 'an unrecorded CPU')}, ISA {isa.get('build', 'not recorded')}, "
             f"{str(m.get('date', ''))[:10]}", ha="right", va="bottom", fontsize=7, color="0.35")
    fig.savefig(out, dpi=110)
    fig.savefig(os.path.splitext(out)[0] + ".svg")
    plt.close(fig)


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    try:
        plot(argv[1], argv[2])
    except PlotError as e:
        print(f"plot_tessellation: {e}", file=sys.stderr)
        return 1
    print(f"wrote {argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
