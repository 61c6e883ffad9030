#!/usr/bin/env python3
"""CPU time of a command: the median of N runs' user + system time, each run's figure printed.

    python3 tests/bench/cpu_median.py N COMMAND [ARG...]
    python3 tests/bench/cpu_median.py 7 build/corsa run FILE.xosc --quiet --duration 1200

The time is the child's own (os.wait4's resource usage), so waiting for a shared core does not
inflate it, unlike wall time. The command's output is discarded; a run that fails stops the
measurement with its exit code. Compare two builds by alternating them in one session, with the
machine's load average beside the figures.
"""

import os
import statistics
import subprocess
import sys


def cpu_ms(command):
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        sys.exit(f"cpu_median: {' '.join(command)} exited with {code}")
    return (usage.ru_utime + usage.ru_stime) * 1000.0


def main():
    if len(sys.argv) < 3 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit("usage: cpu_median.py N COMMAND [ARG...]")
    runs = sorted(cpu_ms(sys.argv[2:]) for _ in range(int(sys.argv[1])))
    load = os.getloadavg()[0]
    print(f"median {statistics.median(runs):.1f} ms CPU of {len(runs)} runs "
          f"({' '.join(f'{r:.1f}' for r in runs)}), load average {load:.1f}")


if __name__ == "__main__":
    main()
