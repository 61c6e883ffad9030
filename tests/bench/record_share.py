#!/usr/bin/env python3
"""The binary recording's share of the long runs, in instructions (callgrind), reproducibly.

    python3 tests/bench/record_share.py [--corsa build/corsa] [--esmini DIR] [--out DIR] [RUN...]

For each run (highway_merge_advanced over 1,200 s, esmini's synchronize, long_standstill,
long_motorway over 300 s; RUN picks some by name) it counts the instructions of `corsa run ...
--quiet --threads 1` under `valgrind --tool=callgrind`, without a trajectory and with
`--record OUT/NAME.corsatraj`, and prints both totals and the recording's share of the run
without it: (with - without) / without. Map loading is in both totals. Instruction counts do
not depend on the machine's load, unlike the CPU time of runs of 20-200 ms (cpu_median.py),
so a change of a few per cent in the recorder shows. Compare two builds by running the script
on each (--corsa). Takes about two minutes.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def runs(esmini):
    xosc = os.path.join(esmini, "resources", "xosc")
    bench = os.path.join(ROOT, "tests", "bench", "scenarios")
    return [
        ("highway_merge_advanced",
         [os.path.join(xosc, "highway_merge_advanced.xosc"), "--duration", "1200"]),
        ("synchronize", [os.path.join(xosc, "synchronize.xosc")]),
        ("long_standstill", [os.path.join(bench, "long_standstill.xosc")]),
        ("long_motorway", [os.path.join(bench, "long_motorway.xosc"), "--duration", "300"]),
    ]


def instructions(command, out_file):
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}"] + command,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    with open(out_file) as f:
        for line in f:
            match = re.match(r"(summary|totals): (\d+)", line)
            if match:
                return int(match.group(2))
    sys.exit(f"record_share: no totals in {out_file}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corsa", default=os.path.join(ROOT, "build", "corsa"))
    parser.add_argument("--esmini", default="/work/notes/esmini",
                        help="esmini's kit (resources/xosc holds its scenarios)")
    parser.add_argument("--out", help="folder for the trajectories and profiles (default: temp)")
    parser.add_argument("names", nargs="*", help="runs to measure (default: all)")
    args = parser.parse_args()
    chosen = [r for r in runs(args.esmini) if not args.names or r[0] in args.names]
    if not chosen:
        sys.exit("record_share: no such run; runs: " +
                 ", ".join(name for name, _ in runs(args.esmini)))
    with tempfile.TemporaryDirectory() as temp:
        out = args.out or temp
        os.makedirs(out, exist_ok=True)
        print(f"{'run':<24}{'without':>16}{'with --record':>16}{'recording':>14}{'share':>8}")
        for name, arguments in chosen:
            base = [args.corsa, "run"] + arguments + ["--quiet", "--threads", "1"]
            without = instructions(base, os.path.join(out, f"{name}.without.cg"))
            trajectory = os.path.join(out, f"{name}.corsatraj")
            with_record = instructions(base + ["--record", trajectory],
                                       os.path.join(out, f"{name}.with.cg"))
            cost = with_record - without
            print(f"{name:<24}{without:>16,}{with_record:>16,}{cost:>14,}"
                  f"{100.0 * cost / without:>7.2f}%", flush=True)


if __name__ == "__main__":
    main()
