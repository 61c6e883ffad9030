#!/usr/bin/env python3
"""Compare Corsa's trajectories with the rows esmini's smoke test asserts.

esmini's own smoke test (test/smoke_test.py of esmini/esmini) runs each scenario with
`--fixed_timestep 0.01` (some with 0.1) and asserts rows of the recorded trajectory:
`time, id, name, x, y, z, h, p, r, speed, ...`. Those rows are esmini's trajectories at sample
points. This tool reads the assertions out of a local copy of smoke_test.py (the kit, outside the
repository: esmini's files at esmini's paths, tests/esmini/FETCHED.md lists them), runs
`corsa run --dt STEP` on every scenario the kit holds, and compares each row with Corsa's
trajectory at the row's time: position (x, y; both sides record the entity's reference point, the
rear axle centre on the ground), heading modulo 2 pi, and speed.

A row is "within" when its position differs by at most 0.5 m; a scenario is "within" when every
one of its rows was compared and the 95th percentile of their position differences is at most
0.5 m and the largest at most 2 m. A row whose time is earlier than one asserted before it in the
same test is marked "rewound": esmini's ghost restarts run the ghost's time again and record rows
with those times, so its trajectory holds such a time twice (Corsa emulates the restarts and
records the same). The smoke test asserts that a line with the row's values is in the file, at
either of its times; so a row is compared with the closer of Corsa's rows of that time and entity
when there are two. Rows are compared and counted alike, rewound or not.

Newer esmini records a ghost's run before a restart as an object of its own, named `<ghost>_-1`
(`_-2` for the run before the second restart, and so on; ids -1, -2, ...), and no longer rewinds
time. Corsa records the ghost as one entity (named `<entity>_ghost`) and rewinds: its rows after a
restart start again at an earlier time, so the ghost's rows fall into runs in recording order, run
0 before the first restart, run N-1 before the N-th. So a row of an entity `X_-N` that Corsa's
trajectory does not name, where X is a ghost (its name ends `_ghost`: Corsa's outputs list no
ghosts otherwise), is compared with Corsa's row of X at its time in run N-1, never with the row of
another run, and marked "earlier run"; a row `Foo_-N` of a Foo that is not a ghost is not mapped.

usage: compare.py [--kit DIR] [--alks DIR] [--corsa BIN] [--extra "ARGS"] [--only NAME] [--rows]
                  [--check-kit] [-v]
Python 3, standard library only.
"""

import argparse
import ast
import csv
import math
import os
import re
import shlex
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WITHIN_M = 0.5
P95_M = 0.5
MAX_M = 2.0


class SmokeRow:
    """One asserted trajectory row, with the test function and the run it comes from."""

    def __init__(self, test, scenario, esmini_args, time, name, x, y, h, speed, text):
        self.test = test
        self.scenario = scenario  # path inside the kit, e.g. resources/xosc/cut-in.xosc
        self.esmini_args = esmini_args  # the esmini options of the test's run
        self.time = time
        self.name = name
        self.x, self.y, self.h, self.speed = x, y, h, speed
        self.text = text  # the assertion's pattern, as the test writes it
        self.rewound = False  # earlier than a row asserted before it in the same test


def logical_lines(text):
    """The file's lines with backslash continuations joined."""
    pending = ''
    for line in text.split('\n'):
        if line.rstrip().endswith('\\'):
            pending += line.rstrip()[:-1] + ' '
            continue
        yield pending + line
        pending = ''
    if pending:
        yield pending


STRING = r"""('(?:\\.|[^'\\])*'|"(?:\\.|[^"\\])*")"""


def literal(token):
    return ast.literal_eval(token)


def module_strings(text):
    """Top-level NAME = 'string' assignments (COMMON_ESMINI_ARGS and the like)."""
    names = {}
    for line in text.split('\n'):
        m = re.match(r'^([A-Z_][A-Z0-9_]*)\s*=\s*' + STRING + r'\s*$', line)
        if m:
            names[m.group(1)] = literal(m.group(2))
    return names


def run_arguments(call, names):
    """The esmini options a run_scenario(...) call passes: its string literals and named strings
    after the scenario path, concatenated as Python would."""
    parts = []
    for m in re.finditer(STRING + r'|\b([A-Z_][A-Z0-9_]*)\b', call):
        if m.group(1):
            parts.append(literal(m.group(1)))
        elif m.group(2) in names and m.group(2) != 'ESMINI_PATH':
            parts.append(names[m.group(2)])
    return ''.join(parts)


def parse_row_pattern(pattern):
    """The fields of an asserted row: '\\n4.050, 1, Target, 128.812, 13.692, ...' with regex
    pieces ('.*' after a truncated number, '-?' before a sign-free zero, '\\+' in names,
    '(0.000|6.283)' for an angle either way)."""
    body = pattern.strip()
    for lead in ('\\n', '^'):
        if body.startswith(lead):
            body = body[len(lead):]
    if body.endswith('\\n'):
        body = body[:-2]
    fields = [f.strip() for f in body.split(', ')]
    if len(fields) < 10:
        return None

    def number(field):
        # '(0.000|6.283)': either value is accepted; the first stands for both (they are one
        # heading, or one roll angle, modulo 2 pi).
        m = re.fullmatch(r'\(([^|()]*)\|[^()]*\)', field)
        if m:
            field = m.group(1)
        # The last field read may run into the pattern's tail ('16.6[67].*,.*'): a comma ends it.
        field = field.split(',')[0].replace('.*', '').replace('-?', '')
        # '16.6[67]': a digit either way; the first stands for both.
        field = re.sub(r'\[(\d)\d*\]', r'\1', field)
        return float(field)

    try:
        return dict(time=number(fields[0]), name=fields[2].replace('\\+', '+'),
                    x=number(fields[3]), y=number(fields[4]), h=number(fields[6]),
                    speed=number(fields[9]))
    except ValueError:
        return None


def scenario_path(prefix, name, names):
    """The scenario a test runs, `os.path.join(PREFIX, 'name')` or `os.path.join(PREFIX + 'name')`:
    a path inside the kit when PREFIX is ESMINI_PATH (esmini's root), else the prefix's value
    joined to the name, normalised (alks_suite.py's ALKS_PREFIX './OSC-ALKS-scenarios/Scenarios/':
    `OSC-ALKS-scenarios/Scenarios/name`, a clone of ASAM's repository beside the test)."""
    if prefix == 'ESMINI_PATH' or prefix not in names:
        return name
    return os.path.normpath(names[prefix] + name)


def read_smoke_rows(path):
    """Every csv row assertion of smoke_test.py (or of a test written the same way, such as
    alks_suite.py), in file order, without repeats of the same row of the same scenario (the
    collision test asserts its rows in two runs of one scenario).
    Rows under `if platform == "win32":` are left out (esmini's random traffic differs between
    platforms; its Linux rows are the ones kept)."""
    text = open(path, encoding='utf-8').read()
    names = module_strings(text)
    rows, seen = [], set()
    test, scenario, args = None, None, ''
    latest = -math.inf
    skip_indent = None
    for line in logical_lines(text):
        indent = len(line) - len(line.lstrip())
        stripped = line.strip()
        if skip_indent is not None and stripped and indent <= skip_indent:
            skip_indent = None
        if re.match(r'(el)?if\s+platform\s*==\s*["\']win32["\']', stripped):
            skip_indent = indent
            continue
        m = re.match(r'def\s+(test_\w+)\s*\(', stripped)
        if m:
            test, scenario, args = m.group(1), None, ''
            latest = -math.inf
            continue
        m = re.search(r"run_scenario\(\s*os\.path\.join\(\s*([A-Z_][A-Z0-9_]*)\s*[,+]\s*" + STRING +
                      r"\s*\)(.*)", stripped)
        if m:
            scenario = scenario_path(m.group(1), literal(m.group(2)), names)
            args = run_arguments(m.group(3), names)
            continue
        if skip_indent is not None or scenario is None:
            continue
        m = re.search(r're\.search\(\s*' + STRING + r'\s*,\s*csv\b', stripped)
        if not m or 'assertFalse' in stripped:
            continue
        pattern = literal(m.group(1))
        fields = parse_row_pattern(pattern)
        if fields is None:
            continue
        key = (scenario, pattern)
        if key in seen:
            continue
        seen.add(key)
        row = SmokeRow(test, scenario, args, fields['time'], fields['name'], fields['x'],
                       fields['y'], fields['h'], fields['speed'], pattern)
        row.rewound = row.time < latest - 1e-9
        latest = max(latest, row.time)
        rows.append(row)
    return rows


ALKS_REPOSITORY = 'OSC-ALKS-scenarios'


def scenario_file(scenario, kit, alks):
    """Where a scenario of the rows is: under `alks` (a copy of ASAM's OSC-ALKS-scenarios) for a
    path inside that repository, in the kit for any other path."""
    head, _, rest = scenario.partition(os.sep)
    if head == ALKS_REPOSITORY and rest:
        return os.path.join(alks, rest)
    return os.path.join(kit, scenario)


def corsa_options(esmini_args):
    """Corsa's options for an esmini run: the step (last --fixed_timestep wins), the seed, and
    --disable-controllers for esmini's --disable_controllers."""
    words = shlex.split(esmini_args)
    step, options = 0.01, []
    for i, word in enumerate(words):
        if word == '--fixed_timestep' and i + 1 < len(words):
            step = float(words[i + 1])
        elif word == '--seed' and i + 1 < len(words):
            options += ['--seed', words[i + 1]]
        elif word == '--disable_controllers':
            options.append('--disable-controllers')
    return step, options


class Trajectory(dict):
    """{(time in ticks of 1 us, entity name): [(x, y, h, speed, run), ...]}, and `rewinds`:
    {entity name: how many times its rows went back in time}."""

    def __init__(self):
        super().__init__()
        self.rewinds = {}


def trajectory_table(rows):
    """The Trajectory of trajectory rows (time s, entity, x, y, h, speed) in recording order. More
    than one row where a ghost restart recorded that time again; `run` counts an entity's rewinds:
    it is 0 until the entity's first row earlier than the entity's row before it, 1 from there to
    the next such row, and so on."""
    table, previous = Trajectory(), {}
    for time, entity, x, y, h, speed in rows:
        tick = round(time * 1e6)
        if entity in previous and tick < previous[entity]:
            table.rewinds[entity] = table.rewinds.get(entity, 0) + 1
        previous[entity] = tick
        table.setdefault((tick, entity), []).append(
            (x, y, h, speed, table.rewinds.get(entity, 0)))
    return table


def read_trajectory(path):
    """trajectory_table of a trajectory CSV."""
    with open(path, newline='') as f:
        return trajectory_table(
            (float(r['time']), r['entity'], float(r['x']), float(r['y']), float(r['h']),
             float(r['speed'])) for r in csv.DictReader(f))


GHOST_RUN = re.compile(r'^(.+_ghost)_-([1-9][0-9]*)$')


def rows_for(trajectory, time, name):
    """Corsa's rows for an asserted row at `time` (s) of entity `name`, and whether it is a ghost's
    earlier run. Esmini's `X_-N` for a ghost X (the ghost's run before its N-th restart, an object
    of its own in newer esmini), when Corsa's trajectory does not name it, is the one row of X at
    that time in run N-1 of Corsa's rows of X (Corsa keeps one entity per ghost and rewinds it at a
    restart), or nothing when Corsa's X was not rewound N times or that run has no row at that
    time."""
    key = round(time * 1e6)
    candidates = trajectory.get((key, name))
    if candidates is not None:
        return candidates, False
    match = GHOST_RUN.match(name)
    if match:
        ghost, run = match.group(1), int(match.group(2)) - 1
        if trajectory.rewinds.get(ghost, 0) <= run:
            return None, False
        same_run = [c for c in trajectory.get((key, ghost), []) if c[4] == run]
        if same_run:
            return same_run, True
    return None, False


def heading_difference(a, b):
    d = math.fmod(a - b, 2 * math.pi)
    if d > math.pi:
        d -= 2 * math.pi
    if d < -math.pi:
        d += 2 * math.pi
    return d


def percentile(values, q):
    """Nearest-rank percentile."""
    ordered = sorted(values)
    rank = max(1, math.ceil(q / 100 * len(ordered)))
    return ordered[rank - 1]


def run_corsa(binary, scenario_path, step, options, extra, out_dir, tag):
    record = os.path.join(out_dir, tag + '.csv')
    command = [binary, 'run', scenario_path, '--dt', repr(step), '--record', record, '--quiet']
    command += options + shlex.split(extra)
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        lines = [l for l in (done.stderr + done.stdout).splitlines() if l.strip()]
        error = lines[-1] if lines else f'exit {done.returncode}'
        return None, ' '.join(command[1:]), error
    return record, ' '.join(command[1:]), None


def check_kit(kit):
    """Compare the kit with the list of fetched files: each file present and of its length."""
    listing = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'FETCHED.md')
    complete = partial = missing = 0
    for line in open(listing, encoding='utf-8'):
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if len(cells) < 3 or not cells[2].isdigit():
            continue
        path, want = os.path.join(kit, cells[0]), int(cells[2])
        if not os.path.isfile(path):
            missing += 1
            print(f'missing  {cells[0]} ({cells[1][:7]}, {want} characters)')
            continue
        with open(path, encoding='utf-8', newline='') as f:
            have = len(f.read())
        if have == want:
            complete += 1
        else:
            partial += 1
            print(f'partial  {cells[0]}: {have} of {want} characters')
    print(f'{complete} files complete, {partial} partial, {missing} missing in {kit}')


def main():
    parser = argparse.ArgumentParser(
        description=__doc__.split('\n')[0],
        epilog="A row of esmini's `X_-N` (newer esmini's object for a ghost X's run before its "
        "N-th restart; X's name ends _ghost) is compared, when Corsa's trajectory names no X_-N, "
        "with Corsa's row of X at its time in the run before X's N-th rewind, and marked "
        "'earlier run'.")
    parser.add_argument('--kit', default='/work/notes/esmini',
                        help="esmini's files at esmini's paths (default /work/notes/esmini)")
    parser.add_argument('--alks', default=os.path.join(REPO, '..', 'shared', 'conformance', 'alks'),
                        help="a copy of ASAM's OSC-ALKS-scenarios, whose scenarios the kit's "
                        "test/alks_suite.py runs (default ../shared/conformance/alks)")
    parser.add_argument('--corsa', default=os.path.join(REPO, 'build', 'corsa'),
                        help='the corsa binary (default build/corsa of this checkout)')
    parser.add_argument('--extra', default='',
                        help='more corsa run options, e.g. "--semantics esmini"')
    parser.add_argument('--only', default='',
                        help='only scenarios or test functions whose name holds this')
    parser.add_argument('--rows', action='store_true', help='print the extracted rows and stop')
    parser.add_argument('--check-kit', action='store_true',
                        help='check the kit against tests/esmini/FETCHED.md and stop')
    parser.add_argument('-v', '--verbose', action='store_true',
                        help='print the corsa command lines')
    args = parser.parse_args()

    if args.check_kit:
        check_kit(args.kit)
        return
    smoke = os.path.join(args.kit, 'test', 'smoke_test.py')
    if not os.path.isfile(smoke):
        sys.exit(f'{smoke}: not found (the kit: tests/esmini/FETCHED.md)')
    rows = read_smoke_rows(smoke)
    alks_suite = os.path.join(args.kit, 'test', 'alks_suite.py')
    if os.path.isfile(alks_suite):
        rows += read_smoke_rows(alks_suite)
    if args.only:
        rows = [r for r in rows if args.only in r.scenario or args.only in r.test]
    if args.rows:
        for r in rows:
            print(f'{r.test}\t{r.scenario}\t{r.esmini_args.strip()}\t{r.text}')
        print(f'{len(rows)} rows over {len({r.scenario for r in rows})} scenarios')
        return

    # One run per scenario and set of esmini options.
    runs = {}
    for r in rows:
        runs.setdefault((r.scenario, r.esmini_args), []).append(r)

    per_scenario = {}  # scenario -> list of (row, distance or None)
    status = {}  # scenario -> 'not in kit' / 'refused: ...'
    with tempfile.TemporaryDirectory(prefix='corsa-esmini-') as out_dir:
        for index, ((scenario, esmini_args), run_rows) in enumerate(runs.items()):
            name = os.path.splitext(os.path.basename(scenario))[0]
            path = scenario_file(scenario, args.kit, args.alks)
            results = per_scenario.setdefault(scenario, [])
            if not os.path.isfile(path):
                status[scenario] = 'not in the kit'
                results += [(r, None) for r in run_rows]
                continue
            step, options = corsa_options(esmini_args)
            record, command, error = run_corsa(args.corsa, path, step, options, args.extra,
                                               out_dir, f'{index}_{name}')
            shown = command if args.verbose else ' '.join(
                ['run', '--dt', repr(step)] + options + shlex.split(args.extra))
            print(f'== {name} ({run_rows[0].test}): corsa {shown}')
            if error:
                status[scenario] = 'did not run: ' + error
                print(f'   did not run: {error}')
                results += [(r, None) for r in run_rows]
                continue
            trajectory = read_trajectory(record)
            for r in run_rows:
                candidates, earlier_run = rows_for(trajectory, r.time, r.name)
                # A ghost's earlier run has one row of its own run; otherwise the smoke test
                # accepts a row at either of its times, so the closer one counts.
                got = None if candidates is None else candidates[0] if earlier_run else min(
                    candidates, key=lambda c: math.hypot(c[0] - r.x, c[1] - r.y))
                if got is None:
                    print(f"   {r.time:8.3f} {r.name:12} no row in Corsa's trajectory")
                    results.append((r, None))
                    continue
                d = math.hypot(got[0] - r.x, got[1] - r.y)
                dh = heading_difference(got[2], r.h)
                dv = got[3] - r.speed
                mark = 'ok' if d <= WITHIN_M else 'FAR'
                if r.rewound:
                    mark += ' (rewound)'
                if earlier_run:
                    mark += ' (earlier run)'
                print(f'   {r.time:8.3f} {r.name:12} d={d:8.3f} m  dh={dh:+.3f} rad  '
                      f'dv={dv:+8.3f} m/s  esmini ({r.x:.3f}, {r.y:.3f}) '
                      f'corsa ({got[0]:.3f}, {got[1]:.3f})  {mark}')
                results.append((r, d))

    print()
    print(f'{"scenario":42} rows within   p95 m    max m  verdict')
    total = within_rows = 0
    ran = within_scenarios = 0
    for scenario, results in per_scenario.items():
        name = os.path.splitext(os.path.basename(scenario))[0]
        n = len(results)
        distances = [d for _, d in results if d is not None]
        ok = sum(1 for d in distances if d <= WITHIN_M)
        total += n
        within_rows += ok
        if scenario in status:
            print(f'{name:42} {n:4} {ok:6}        -        -  {status[scenario]}')
            continue
        ran += 1
        p95 = percentile(distances, 95) if distances else math.inf
        worst = max(distances) if distances else math.inf
        good = len(distances) == n and p95 <= P95_M and worst <= MAX_M
        within_scenarios += good
        missing = n - len(distances)
        rewound = sum(1 for r, _ in results if r.rewound)
        verdict = 'within' if good else 'differs'
        if missing:
            verdict += f' ({missing} rows missing)'
        if rewound:
            verdict += f' ({rewound} rows rewound)'
        print(f'{name:42} {n:4} {ok:6} {p95:8.3f} {worst:8.3f}  {verdict}')
    print()
    in_kit = [s for s in per_scenario if status.get(s) != 'not in the kit']
    kit_rows = sum(len(per_scenario[s]) for s in in_kit)
    print(f'{within_rows} of {total} rows within {WITHIN_M} m ({kit_rows} rows of the '
          f'{len(in_kit)} scenarios in the kit); {within_scenarios} of {ran} scenarios that ran '
          f'within p95 {P95_M} m / max {MAX_M} m ({len(per_scenario)} scenarios with rows)')


if __name__ == '__main__':
    main()
