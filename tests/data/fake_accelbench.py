#!/usr/bin/python3
"""A stand-in for accelbench in tests of scripts/bench_embree's two-thread render: `gen` writes an
empty scene, `render ... --threads N --stats FILE` writes statistics whose render_ms is 200 ms for
one thread and FAKE_TWO_THREAD_MS (default 104) for two, with the same image hash."""

import json
import os
import sys

args = sys.argv[1:]
if args[0] == "gen":
    with open(args[args.index("-o") + 1], "w") as f:
        f.write("{}\n")
    sys.exit(0)
threads = int(args[args.index("--threads") + 1])
ms = 200.0 if threads == 1 else float(os.environ.get("FAKE_TWO_THREAD_MS", "104"))
with open(args[args.index("--stats") + 1], "w") as f:
    json.dump({"timings": {"build_ms": 2.0, "render_ms": ms}, "image_hash": "0123"}, f)
