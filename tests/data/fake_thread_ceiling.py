#!/usr/bin/python3
"""A stand-in for bench/thread_ceiling in tests of scripts/bench_embree: `--load L --pairs N --json
FILE` writes N pairs whose ratio is FAKE_CEILING (default 1.95), or for --load vector
FAKE_CEILING_VECTOR (default 1.9)."""

import json
import os
import sys

args = sys.argv[1:]
pairs = int(args[args.index("--pairs") + 1])
vector = args[args.index("--load") + 1] == "vector"
ratio = float(os.environ.get("FAKE_CEILING_VECTOR", "1.9") if vector else os.environ.get("FAKE_CEILING", "1.95"))
with open(args[args.index("--json") + 1], "w") as f:
    json.dump({"pairs": [{"one_ms": 200.0, "two_ms": 200.0 / ratio, "ratio": ratio}] * pairs}, f)
