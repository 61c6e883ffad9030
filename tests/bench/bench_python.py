#!/usr/bin/env python3
"""Timing of the corsa Python module: what a Python loop adds to each step, and states().

    PYTHONPATH=build/python /usr/bin/python3 tests/bench/bench_python.py

Per-step overhead: the same scenario stepped to its end by `while sim.step(): pass` from Python
and by sim.run() (the loop in C++), the difference divided by the steps (target <= 2 us).
states(): one call with 1,000 entities (scenarios/town04_junction.xosc with 998 seeded NPC
vehicles; target <= 50 us). CPU time of this process (time.process_time: what waiting for a shared core does not
inflate), medians of several runs, each printed with its range; compare figures of one run only.
"""

import statistics
import time
from pathlib import Path

import corsa

ROOT = Path(__file__).resolve().parents[2]
CUT_IN = ROOT / "scenarios/cut_in.xosc"


def seconds(work, repeat):
    """Median and range of `repeat` CPU timings of work() (seconds)."""
    times = []
    for _ in range(repeat):
        start = time.process_time()
        work()
        times.append(time.process_time() - start)
    return statistics.median(times), min(times), max(times)


def step_overhead(repeat=15):
    steps = corsa.Simulation(CUT_IN).run()["steps"]

    def from_python():
        sim = corsa.Simulation(CUT_IN)
        while sim.step():
            pass

    def in_cpp():
        corsa.Simulation(CUT_IN).run()

    load = seconds(lambda: corsa.Simulation(CUT_IN), repeat)[0]
    python = seconds(from_python, repeat)
    cpp = seconds(in_cpp, repeat)
    per_step = (python[0] - cpp[0]) / steps * 1e6
    print(f"cut_in.xosc, {steps} steps (load {load * 1e3:.2f} ms, subtracted from neither):")
    print(f"  Python loop of sim.step(): {python[0] * 1e3:.2f} ms "
          f"({python[1] * 1e3:.2f}..{python[2] * 1e3:.2f})")
    print(f"  sim.run():                 {cpp[0] * 1e3:.2f} ms "
          f"({cpp[1] * 1e3:.2f}..{cpp[2] * 1e3:.2f})")
    print(f"  overhead per sim.step():   {per_step:.2f} us (target <= 2 us)")


def states_call(repeat=201):
    sim = corsa.Simulation(ROOT / "scenarios/town04_junction.xosc", npc={"vehicles": 998})
    for _ in range(10):
        sim.step()
    sim.states()  # the first call imports numpy and makes the record type
    count = len(sim.entities)
    median, low, high = seconds(sim.states, repeat)
    print(f"states() of {count} entities: {median * 1e6:.1f} us "
          f"({low * 1e6:.1f}..{high * 1e6:.1f}; target <= 50 us)")


if __name__ == "__main__":
    step_overhead()
    states_call()
