"""What stepping from Python costs against the loop in C++, and the time per sample of
examples/python/make_dataset.py (docs/PERFORMANCE.md, "Python"). Measures, does not assert.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--steps 10000] [--repeats 5]

Per repeat, interleaved: Simulator.step(N) once (the loop in C++, the GIL released), N calls of
Simulator.step(1) from a Python loop, and N calls of step(1) + positions() (a copy of the (n, 3)
positions each step). Prints one JSON object: medians (s) and the per-step overhead of the Python
call, (loop − batch) / N, and its ratio to the C++ step. Then make_dataset.py with --n 200 (a warm
basis cache) timed as a whole process.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import myoshell


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=10000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--samples", type=int, default=200, help="make_dataset.py --n")
    args = parser.parse_args()

    cache = tempfile.mkdtemp(prefix="myo_pybench_")
    face = myoshell.Face(cache=cache)  # the built-in head, the whole face's 40 muscles
    sim = myoshell.Simulator(face)
    sim.set_activations({"zygomaticus_major_left": 0.7, "corrugator_supercilii_right": 0.4})
    n = args.steps
    batch, loop, loop_read = [], [], []
    for _ in range(args.repeats):
        sim.reset()
        t = time.perf_counter()
        sim.step(n)
        batch.append(time.perf_counter() - t)
        sim.reset()
        t = time.perf_counter()
        for _ in range(n):
            sim.step(1)
        loop.append(time.perf_counter() - t)
        sim.reset()
        t = time.perf_counter()
        for _ in range(n):
            sim.step(1)
            sim.positions()
        loop_read.append(time.perf_counter() - t)
    b, l, lr = statistics.median(batch), statistics.median(loop), statistics.median(loop_read)

    here = os.path.dirname(os.path.abspath(__file__))
    example = os.path.join(here, "..", "examples", "python", "make_dataset.py")
    out = os.path.join(cache, "faces.npz")
    env = dict(os.environ)
    command = [sys.executable, example, "--n", str(args.samples), "--out", out, "--cache", cache]
    subprocess.run(command, check=True, env=env, capture_output=True)  # warms nothing more: the cache is warm
    t = time.perf_counter()
    subprocess.run(command, check=True, env=env, capture_output=True)
    dataset = time.perf_counter() - t

    print(json.dumps({
        "vertices": int(sim.rest_positions().shape[0]),
        "steps": n,
        "repeats": args.repeats,
        "batch_seconds": b,
        "python_loop_seconds": l,
        "python_loop_with_positions_seconds": lr,
        "cxx_step_us": 1e6 * b / n,
        "python_call_overhead_us": 1e6 * (l - b) / n,
        "overhead_over_step": (l - b) / b,
        "positions_copy_us": 1e6 * (lr - l) / n,
        "dataset_samples": args.samples,
        "dataset_seconds": dataset,
        "dataset_seconds_per_sample": dataset / args.samples,
    }, indent=2))


if __name__ == "__main__":
    main()
