#!/usr/bin/python3
"""How well does a progressive photon mapping reference know its own error?

Makes the ppm references of the photon fronts (plain and Richardson, at N and 8N passes) through
`accelbench fronts`, which also estimates each one's floor from its own stages
(harness/reference_floor.h), and measures each one's actual error against a much longer run:
two independent renders of 64N passes (other seeds), combined by Richardson extrapolation. Writes
results/ppm_reference_floor.{json,png,svg} (docs/accuracy.md, "Measured").

    scripts/ppm_reference_study.py [--scene glass_caustic] [--passes 256] [--photons 10000]
                                   [--resolution 160x120] [--set KEY=VALUE ...]
                                   [--work build/ppm_study] [--out results] [--stem ppm_reference_floor]

--set gives a ppm knob to every render, references and truth alike (on the ring,
max_paths: docs/accuracy.md).

Resumable: every render is kept under --work and not made again.
"""

import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RATIO = 8  # harness/reference_floor.h kStageRatio
TRUTH_SEEDS = (0x7e57_0001, 0x7e57_0002)  # independent of the references' halves


def fail(message):
    print(f"ppm_reference_study: {message}", file=sys.stderr)
    sys.exit(1)


def run(cmd):
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        fail(f"{' '.join(cmd)} failed: {result.stdout.strip().splitlines()[-1] if result.stdout.strip() else ''}")
    return result.stdout


def read_pfm(path):
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            fail(f"{path}: not a colour PFM")
        w, h = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    if data.size != w * h * 3:
        fail(f"{path}: truncated")
    return np.flipud(data.reshape(h, w, 3)).astype(np.float64)


def machine_name():
    """The CPU and its widest vector ISA, for the figure's title."""
    model, flags = "unknown CPU", ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name") and model == "unknown CPU":
                    model = line.split(":", 1)[1].strip()
                if line.startswith("flags") and not flags:
                    flags = line
    except OSError:
        pass
    isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "SSE"
    return f"{model}, {os.cpu_count()} cores, {isa}"


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("--scene", default="glass_caustic")
    ap.add_argument("--passes", type=int, default=256, help="N: the base reference's passes")
    ap.add_argument("--photons", type=int, default=10000, help="photons per map per pass")
    ap.add_argument("--resolution", default="160x120")
    ap.add_argument("--bin", default=os.path.join(REPO, "build", "bin", "accelbench"))
    ap.add_argument("--work", default=os.path.join(REPO, "build", "ppm_study"))
    ap.add_argument("--out", default=os.path.join(REPO, "results"))
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a ppm knob for every render (references and truth)")
    ap.add_argument("--stem", default="ppm_reference_floor", help="the results' file name, before .json/.png/.svg")
    args = ap.parse_args()
    for kv in args.set:
        if "=" not in kv or kv.startswith("="):
            fail(f"--set: expected KEY=VALUE, got '{kv}'")
    if args.passes % (RATIO * RATIO) != 0:
        fail(f"--passes must be divisible by {RATIO * RATIO}, got {args.passes}")
    os.makedirs(args.work, exist_ok=True)
    cache = os.path.join(args.work, "references")
    tag = "-".join([args.scene, str(args.passes), str(args.photons), args.resolution] + args.set)

    # The references, each with its own floor estimate, as the fronts make them.
    refs = {}
    for passes in (args.passes, RATIO * args.passes):
        for estimator in ("plain", "richardson"):
            out = os.path.join(args.work, f"front-{tag}-{estimator}-{passes}.json")
            if not os.path.exists(out):
                print(f"reference: {estimator}, {passes} passes", file=sys.stderr)
                run([args.bin, "fronts", args.scene, "--integrator", "photon", "--knobs", "k", "--values", "k=50",
                     "--seeds", "1", "--repetitions", "1", "--warmup", "0", "--resolution", args.resolution,
                     "--estimator", estimator, "--reference-set", f"passes={passes}",
                     "--reference-set", f"photons_per_pass={args.photons}"]
                    + [a for kv in args.set for a in ("--reference-set", kv)]
                    + ["--cache", cache, "--out", out, "--quiet"])
            with open(out) as f:
                front = json.load(f)["fronts"][0]
            ref = front["reference"]
            refs[(estimator, passes)] = {"floor": ref["floor"], "image": read_pfm(os.path.join(cache, ref["key"] + ".pfm")),
                                         "key": ref["key"]}

    # The truth: 64N passes twice with other seeds, Richardson-combined with their 8N checkpoints.
    long_passes = RATIO * RATIO * args.passes
    scene_file = os.path.join(args.work, f"{args.scene}.json")
    if not os.path.exists(scene_file):
        run([args.bin, "gen", args.scene, "-o", scene_file])
    halves = []
    for seed in TRUTH_SEEDS:
        pfm = os.path.join(args.work, f"truth-{tag}-{seed:x}.pfm")
        check = pfm[:-4] + f".{RATIO * args.passes}.pfm"
        if not (os.path.exists(pfm) and os.path.exists(check)):
            print(f"truth: {long_passes} passes, seed {seed:#x}", file=sys.stderr)
            run([args.bin, "render", scene_file, "--integrator", "ppm", "--accel", "bvh", "--resolution", args.resolution,
                 "--param", f"passes={long_passes}", "--param", f"photons_per_pass={args.photons}",
                 "--param", f"seed={seed}", "--threads", "0", "--pfm", pfm, "--checkpoints", str(RATIO * args.passes)]
                + [a for kv in args.set for a in ("--param", kv)])
        halves.append((read_pfm(pfm), read_pfm(check)))
    g = RATIO ** (1.0 / 3.0)  # ppm's bias order at its default alpha 2/3
    rich_halves = [(g * n - n8) / (g - 1.0) for n, n8 in halves]
    truth = 0.5 * (rich_halves[0] + rich_halves[1])
    truth_noise = rmse(rich_halves[0], rich_halves[1]) / 2.0
    plain_truth = 0.5 * (halves[0][0] + halves[1][0])

    rows = []
    for (estimator, passes), r in sorted(refs.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        measured = rmse(r["image"], truth)
        # The truth's own noise is independent of the reference: it adds in quadrature.
        actual = math.sqrt(max(0.0, measured ** 2 - truth_noise ** 2))
        f = r["floor"]
        rows.append({"estimator": estimator, "passes": passes, "floor": f["rmse"], "noise": f["noise_rmse"],
                     "bias_upper": f.get("bias_rmse", 0.0), "bias_estimate": f.get("bias_rmse_estimate", 0.0),
                     "rmse_against_truth": measured, "actual_error": actual,
                     "floor_over_actual": f["rmse"] / actual if actual > 0 else None})
    summary = {"scene": args.scene, "resolution": args.resolution, "photons_per_pass": args.photons, "set": args.set,
               "truth": {"passes": long_passes, "estimator": "richardson", "seeds": list(TRUTH_SEEDS),
                         "noise_rmse": truth_noise, "plain_minus_richardson_rmse": rmse(plain_truth, truth)},
               "references": rows}
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, f"{args.stem}.json"), "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    print(f"{'estimator':>10} {'passes':>7} {'floor':>9} {'noise':>9} {'bias<=':>9} {'actual':>9} {'floor/actual':>12}")
    for r in rows:
        ratio = r["floor_over_actual"]
        print(f"{r['estimator']:>10} {r['passes']:>7} {r['floor']:9.4g} {r['noise']:9.4g} {r['bias_upper']:9.4g} "
              f"{r['actual_error']:9.4g} {ratio if ratio is None else round(ratio, 2)!s:>12}")
    print(f"truth: {long_passes} passes, noise {truth_noise:.3g}; plain and richardson truths differ by "
          f"{summary['truth']['plain_minus_richardson_rmse']:.3g}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def blocks(err, k=4):
        h, w = err.shape[0] // k * k, err.shape[1] // k * k
        return err[:h, :w].reshape(h // k, k, w // k, k).mean(axis=(1, 3))

    fig = plt.figure(figsize=(15, 7), layout="constrained")
    top = fig.subfigures(2, 1, height_ratios=[1.0, 1.1])
    axes = top[0].subplots(1, 4)
    axes[0].imshow(np.clip(truth / max(1e-9, np.percentile(truth, 99)), 0, 1) ** (1 / 2.2))
    axes[0].set_title(f"truth: Richardson of {long_passes} passes", fontsize=9)
    err = {}
    for key in (("plain", args.passes), ("richardson", args.passes)):
        err[key] = blocks(np.abs(refs[key]["image"] - truth).mean(axis=2))
    vmax = max(float(np.percentile(e, 99.5)) for e in err.values())
    for ax, (key, e) in zip(axes[1:3], err.items()):
        im = ax.imshow(e, vmin=0, vmax=vmax, cmap="magma")
        ax.set_title(f"|{key[0]}, {key[1]} passes - truth| (4x4 mean)", fontsize=9)
    top[0].colorbar(im, ax=axes[1:3], fraction=0.03)
    # Where the cancellation helps (blue) and where it fails (red).
    diff = err[("richardson", args.passes)] - err[("plain", args.passes)]
    lim = max(1e-12, float(np.percentile(np.abs(diff), 99.5)))
    im2 = axes[3].imshow(diff, vmin=-lim, vmax=lim, cmap="coolwarm")
    axes[3].set_title("richardson - plain error (red: richardson worse)", fontsize=9)
    top[0].colorbar(im2, ax=axes[3], fraction=0.046)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    # Each reference's estimated floor against its actual error.
    bar = top[1].subplots(1, 1)
    labels = [f"{r['estimator']}\n{r['passes']} passes" for r in rows]
    x = np.arange(len(rows))
    bar.bar(x - 0.3, [r["noise"] for r in rows], 0.2, label="estimated noise", color="#9ecae1")
    bar.bar(x - 0.1, [r["bias_upper"] for r in rows], 0.2, label="estimated bias (95% upper)", color="#fdae6b")
    bar.bar(x + 0.1, [r["floor"] for r in rows], 0.2, label="floor = sqrt(noise² + bias²)", color="#3182bd")
    bar.bar(x + 0.3, [r["actual_error"] for r in rows], 0.2, label="actual error (against the truth)", color="#d62728")
    bar.set_xticks(x, labels)
    bar.set_ylabel("RMSE (radiance)")
    bar.legend(fontsize=8)
    bar.set_title("estimated floor against actual error; the truth's own noise "
                  f"({truth_noise:.3g}) removed in quadrature", fontsize=9)
    fig.suptitle(f"ppm references on {args.scene}, {args.photons} photons per map per pass, {args.resolution}"
                 f"{''.join(', ' + kv for kv in args.set)}; "
                 f"{machine_name()}", fontsize=9)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(args.out, f"{args.stem}.{ext}"), dpi=80)
    print(f"wrote {args.out}/{args.stem}.{{json,png,svg}}")


if __name__ == "__main__":
    main()
