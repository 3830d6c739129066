#!/usr/bin/env python3
# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Times strata's Field.evaluate on 1 M points of the default scene's region,
one thread, and prints it beside what the C++ block path takes for the same
points (build/tests/bench/terrain_bench --benchmark_filter=DefaultFieldBlocks,
the same point generator). Issue 28's goal: within 1.2x.

    PYTHONPATH=build/python python3 python/bench/evaluate_bench.py [--cpp build/tests/bench/terrain_bench]
"""

import argparse
import json
import subprocess
import time

import numpy as np

import strata


def points(count):
    """The bench's LCG (TerrainBench.cpp), in NumPy's wrapping uint64."""
    state = np.uint64(1)
    mul, inc = np.uint64(6364136223846793005), np.uint64(1442695040888963407)
    raw = np.empty(3 * count, dtype=np.uint64)
    with np.errstate(over="ignore"):
        for i in range(3 * count):
            state = state * mul + inc
            raw[i] = state
    unit = (raw >> np.uint64(11)).astype(np.float64) * 2.0 ** -53
    extent = np.tile([192.0, 88.0, 192.0], count)
    return (extent * unit - 0.5 * extent).reshape(count, 3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cpp", help="terrain_bench executable, to run the C++ side in the same go")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    pts = points(1_000_000)
    field = strata.default_scene().field
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        values = field.evaluate(pts, threads=1)
        times.append(time.perf_counter() - start)
    best = min(times)
    print(f"python evaluate, 1 M points, 1 thread: best {best * 1e3:.1f} ms of {args.repeat}, checksum {values.sum():.6f}")
    if args.cpp:
        out = subprocess.run([args.cpp, "--benchmark_filter=DefaultFieldBlocks", "--benchmark_format=json",
                              f"--benchmark_repetitions={args.repeat}"], capture_output=True, text=True, check=True)
        runs = [b for b in json.loads(out.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
        cpp = min(b["real_time"] for b in runs) / 1e3  # ms -> s
        print(f"C++ block path, same points:           best {cpp * 1e3:.1f} ms, checksum {runs[0]['checksum']:.6f}")
        print(f"ratio python / C++: {best / cpp:.3f}")


if __name__ == "__main__":
    main()
