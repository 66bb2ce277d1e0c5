#!/usr/bin/python3
"""A stand-in for accelbench in tests of scripts/bench_embree's two-thread render: `gen` writes an
empty scene, `render ... --threads N --stats FILE` writes statistics whose render_ms is 200 ms for
one thread and, for two, FAKE_TWO_THREAD_MS (default 104) or, when FAKE_TWO_THREAD_MS_LIST is set
(comma-separated), its values in turn, one per two-thread render (the last one repeated), with the
same image hash."""

import json
import os
import sys

args = sys.argv[1:]
if args[0] == "gen":
    with open(args[args.index("-o") + 1], "w") as f:
        f.write("{}\n")
    sys.exit(0)
threads = int(args[args.index("--threads") + 1])
stats = args[args.index("--stats") + 1]
ms = 200.0
if threads == 2:
    ms = float(os.environ.get("FAKE_TWO_THREAD_MS", "104"))
    listed = os.environ.get("FAKE_TWO_THREAD_MS_LIST")
    if listed:
        values = [float(v) for v in listed.split(",")]
        counter = os.path.join(os.path.dirname(stats), "fake_two_thread_calls")
        calls = int(open(counter).read()) if os.path.exists(counter) else 0
        with open(counter, "w") as f:
            f.write(str(calls + 1))
        ms = values[min(calls, len(values) - 1)]
with open(stats, "w") as f:
    json.dump({"timings": {"build_ms": 2.0, "render_ms": ms}, "image_hash": "0123"}, f)
