#!/usr/bin/python3
"""Figure of the stability suite (`accelbench stability ... --out FILE.json`), one file per scene.

Writes results/stability.{png,svg}: for each scene, the share of pixels more than 1% off the
untransformed render against the translation distance 10^k (along x, and along the diagonal) and
against the scale factor 10^k, one solid line for the float renderer and one dashed line for the
double-precision reference (naive in double), with the suite's thresholds as grey bars. A point on
the floor of the log axis (1e-4) is an image equal to the base within 1% everywhere. Structures
that disagree with naive are listed in the title of their scene's panel.

Usage: scripts/plot_stability.py results/stability-five.json ... [--out results]
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot import machine_note  # noqa: E402

FLOOR = 1e-4  # drawn in place of 0 on the log axis
GROUPS = [("translate_x", "translated along x by 10^k"),
          ("translate_diag", "translated along (1,-1,1) by 10^k"),
          ("scale", "scaled by 10^k")]


def scene_name(doc):
    name = os.path.splitext(os.path.basename(doc["scene"]))[0]
    params = doc.get("integrator_params") or {}
    if params:  # the same scene with other integrator knobs (triangle=moller) is a panel of its own
        name += " (" + ", ".join(f"{k}={v}" for k, v in sorted(params.items())) + ")"
    return name


def series(doc, group, precision):
    xs, ys = [], []
    for v in doc["variants"]:
        if v["group"] != group or v[precision] is None or v[precision]["vs_base"] is None:
            continue
        xs.append(v["exponent"])
        ys.append(max(FLOOR, v[precision]["vs_base"]["fraction_off"]))
    return xs, ys


def target_points(group):
    """The issue's pixel targets: <= 1% up to 10^4 (and scales 10^-4..10^4), <= 5% at 10^5."""
    if group == "scale":
        return [k for k in range(-4, 5) if k != 0], [0.01] * 8
    return [1, 2, 3, 4, 5], [0.01, 0.01, 0.01, 0.01, 0.05]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--out", default="results")
    args = ap.parse_args()
    docs = []
    for f in args.files:
        try:
            with open(f) as fh:
                doc = json.load(fh)
        except (OSError, ValueError) as e:
            sys.exit(f"plot_stability: {f}: {e}")
        if doc.get("kind") != "accelbench-stability":
            sys.exit(f"plot_stability: {f}: not an accelbench stability file")
        docs.append(doc)

    same_size = len({tuple(doc["resolution"]) for doc in docs}) == 1
    fig, axes = plt.subplots(len(docs), len(GROUPS), figsize=(4.2 * len(GROUPS), 2.6 * len(docs)),
                             squeeze=False, sharey=True)
    for row, doc in enumerate(docs):
        bad = sorted({s["label"] for v in doc["variants"] for s in v["structures"]
                      if not (s["equal_image"] and s["equal_rays"])})
        for col, (group, title) in enumerate(GROUPS):
            ax = axes[row][col]
            for precision, style, color in [("float", "-o", "tab:blue"), ("double", "--s", "tab:orange")]:
                xs, ys = series(doc, group, precision)
                if xs:
                    ax.plot(xs, ys, style, color=color, markersize=3.5, label=precision)
            tx, ty = target_points(group)
            ax.plot(tx, ty, "_", color="0.45", markersize=14, markeredgewidth=1.5, label="target")
            ax.set_yscale("log")
            ax.set_ylim(FLOOR * 0.7, 1.0)
            ax.grid(True, which="major", alpha=0.3)
            ax.set_xticks(range(-6, 7) if group == "scale" else range(1, 7))
            if row == len(docs) - 1:
                ax.set_xlabel("k (" + title + ")")
            if col == 0:
                # Rows measured at different image sizes say their own.
                size = "" if same_size else "{}x{}: ".format(*doc["resolution"])
                ax.set_ylabel(scene_name(doc) + "\n" + size + "pixels > 1% off")
            if row == 0 and col == 0:
                ax.legend(fontsize=7, loc="upper left")
            if col == 1:
                status = ("structures = naive on every variant" if not bad
                          else "differ from naive: " + ", ".join(bad))
                ax.set_title(status, fontsize=8, color="black" if not bad else "red")
    res = docs[0]["resolution"]
    setting = f"{res[0]}x{res[1]}, " if same_size else ""
    fig.suptitle(f"Stability: whole scenes moved and scaled, float renderer against the double "
                 f"reference ({setting}{docs[0]['integrator']})", fontsize=10)
    fig.tight_layout()
    note = machine_note([doc.get("machine") for doc in docs])
    if note:
        fig.text(0.99, 0.0, note, ha="right", va="top", fontsize=7, color="0.35")
    os.makedirs(args.out, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(args.out, "stability." + ext), dpi=90, bbox_inches="tight")
    print(os.path.join(args.out, "stability.{png,svg}"))


if __name__ == "__main__":
    main()
