#!/usr/bin/env python3
"""A time-boxed mutation campaign of the `corsa` binary on inputs the corpus does not cover.

Each case copies its source folder into a scratch workspace, breaks one file there (XML-aware:
elements deleted, duplicated, swapped, moved or nested thousands deep; attribute values made
huge, negative, NaN, inf, empty, unicode, bad `${...}` expressions or deleted; parameters that
reference themselves, a distribution or catalog that names itself; for maps: geometry lengths
0, negative or 1e300, every lane 0 m wide, roads linked to themselves, junction cycles;
byte-level: truncation and flipped bytes; NGII `.dbf`/`.shp`/`.shx`: flipped bytes, truncation,
header counts and field texts overwritten) and runs one command on it from a fresh folder, under
a time limit and `prlimit --as`:

  xosc   esmini kit scenarios (and their maps and catalogs), ../shared/conformance/alks and
         asam-osc-1.3: `validate`, `run --duration 5`, `run --rig` on a tiny rig, `sweep
         SCENARIO --param` on a grid of two
  xodr   ../shared/data/xodr maps: `validate`, `map info|mesh|render|query|holes`
  ngii   K-City layers: `convert ngii -o --report`
  sweep  a 4-variant distribution and the ALKS/ASAM distributions: `sweep -o` (one shard of 50)
  rig    the tiny rig: `run --rig -o`

A case fails ("finding") on: a signal or an exit code other than 0 (ok), 1 (scenario failed) and
2 (bad input); the time limit; exit 2 without an error located at `file:line`, `file: record N`
or, for a path, `file: error:`; an error line that is not located; a file written, changed or
removed outside the output folder (the workspace and the working folder are compared before and
after); after exit 2, anything left in the output folder; after any exit, a temporary or lock
file left behind. Every case is made from (seed, case number) alone, so `--case N` replays one.

usage: campaign.py [--corsa BIN] [--budget N] [--seed S] [--families a,b] [--timeout SEC]
                   [--memory BYTES] [--findings DIR] [--case N] [-v]
The CI run (ctest label `campaign`): `--budget 40`. The long campaign (by hand):
  python3 tests/robustness/campaign.py --budget 3000 --findings /tmp/campaign-findings
Exit 0 when no case failed, 1 otherwise. Python 3, standard library only.

This file is the command line; the mutations, the sources per reader and the runner of one case
are the modules of mutation_campaign/ (its __init__.py lists them).
"""

import argparse
import os
import shutil
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ left in the source tree by a run
from mutation_campaign.runner import run_case  # noqa: E402
from mutation_campaign.sources import REPO, sources  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--corsa', default=os.path.join(REPO, 'build', 'corsa'))
    parser.add_argument('--budget', type=int, default=40, help='cases to run')
    parser.add_argument('--seed', type=int, default=16)
    parser.add_argument('--families', default='', help='comma list: xosc,xodr,ngii,sweep,rig')
    parser.add_argument('--timeout', type=float, default=20)
    parser.add_argument('--memory', default=str(2 << 30), help='address space limit (bytes)')
    parser.add_argument('--findings', default='', help='folder to keep each failing case in')
    parser.add_argument('--case', type=int, action='append', help='replay these case numbers')
    parser.add_argument('--keep', action='store_true', help='keep every case in --findings')
    parser.add_argument('--scratch', default='', help='parent of the scratch folder')
    parser.add_argument('-v', '--verbose', action='store_true')
    args = parser.parse_args()
    sys.setrecursionlimit(10000)  # ElementTree writes a 900-deep nest recursively
    args.corsa = os.path.abspath(args.corsa)
    if not os.access(args.corsa, os.X_OK):
        print(f'campaign: no corsa binary at {args.corsa}', file=sys.stderr)
        return 2
    if shutil.which('prlimit') is None:
        print('campaign: prlimit (util-linux) is needed', file=sys.stderr)
        return 2
    all_sources = sources()
    if args.families:
        wanted = set(args.families.split(','))
        all_sources = [s for s in all_sources if s.family in wanted]
    numbers = args.case if args.case else range(args.budget)
    failures = 0
    counts = {}
    with tempfile.TemporaryDirectory(prefix='corsa-campaign-', dir=args.scratch or None) as scratch:
        for number in numbers:
            record = run_case(args, number, all_sources, scratch)
            key = (record['family'], str(record['exit']))
            counts[key] = counts.get(key, 0) + 1
            if record['problems']:
                failures += 1
                print(f"FAIL case {number} [{record['family']}] {record['file']}: {record['mutation']}\n"
                      f"  (cd {record['folder']}) {record['command']}\n  exit {record['exit']}: "
                      + '; '.join(record['problems']) + '\n  ' + record['stderr'][-600:].replace('\n', '\n  '))
            elif args.verbose:
                print(f"ok case {number} [{record['family']}] exit {record['exit']} "
                      f"{record['seconds']} s {record['file']}: {record['mutation'][:80]}")
    summary = ', '.join(f'{family} exit {code}: {n}' for (family, code), n in sorted(counts.items()))
    print(f'{len(numbers)} cases, {failures} failing ({summary})')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
