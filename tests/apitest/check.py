#!/usr/bin/env python3
"""Check `corsa validate` against the bad-input files of ASAM's OpenSCENARIO API tester.

The API tester (github.com/RA-Consulting-GmbH/openscenario.api.test) ships files that break the
standard on purpose and, in its own test sources, the messages its reader must give for each:
line, column and text. The kit (outside the repository: third-party files; default
/work/notes/apitest, its FETCHED.md lists them) holds those files and `expected.json`:
`{"files": {"NAME.xosc": [{"line": N, "message": "..."}, ...] | null}}` (null: the tester
lists no message for that file; Corsa's errors are then listed, nothing is counted).

For every kit file this runs `corsa validate FILE` and reports, per expected message, whether
Corsa gives an error at that line and whether it names roughly the same cause (a small table of
cause words: a value that is not a number or not of the type, an enumeration value not allowed,
an unknown element, division by zero, overflow, an expression's syntax, a deprecated attribute,
an undefined name, a ModifyAction on a non-numeric variable, a value breaking its parameter's
constraints, a missing or extra child element, ...). Corsa's errors at lines the
tester names no message for are listed as Corsa-only: those about a map or catalog the kit lacks
(the tester's reader does not open referenced files; the tester's repository does not hold them
either) apart from the rest, which are the false positives to read. A bad file must exit 2 and a
good one (`--good DIR`, default ../shared/conformance beside the repository when present: files
that must load) 0; anything else, a crash included, is a failure. An expected message Corsa
answers with a lenient reading at its line (a `(read as ...)` warning: the file runs as its
author meant; `--strict` makes it an error) is counted apart.

usage: check.py [--kit DIR] [--corsa BIN] [--good DIR ...] [--no-good] [--strict] [-v]
Exit 0 when every file ran with the exit code it should; 1 otherwise; 0 with a note when the kit
is absent. Python 3, standard library only.
"""

import argparse
import json
import os
import re
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_KIT = '/work/notes/apitest'
DIAGNOSTIC_LINE = re.compile(r'^(?P<file>.+?):(?P<line>\d+): (?P<severity>error|warning): '
                             r'(?P<message>.*)$')

# Cause words: a class holds when the tester's (first pattern) or Corsa's (second) text matches.
CAUSES = [
    ('value', r'cannot convert|cannot be parsed|cannot be converted|number format|must be numeric|'
     r'not supported type',
     r'is not a number|is not a valid|cannot be set|cannot be used in an expression|needs numbers|'
     r'is not an? '),
    ('enumeration', r'is not allowed', r'is not a valid'),
    ('unknown element', r'unknown element', r'unknown element'),
    ('division by zero', r'division by zero', r'division by zero'),
    ('square root', r'square root', r'sqrt'),
    ('power', r'raising', r'pow'),
    ('overflow', r'overflow', r'overflow|out of range'),
    ('syntax', r'syntax error', r'bad number|unexpected character|syntax|bad expression'),
    ('deprecated', r'deprecated', r'deprecated|written together|twice'),
    ('undefined', r'not defined|cannot resolve', r'not defined|undefined|unknown|not declared'),
    ('modify', r'modifyaction', r'modifyaction'),
    ('constraint', r'value constraint', r'violates its value constraints'),
    ('cardinality', r'too few children|one of these properties is required',
     r'without <|needs one of|takes one child'),
    ('malformed', r'endtag|end-tag|must be terminated|beendet|entity', r'malformed xml'),
]
# Corsa's errors about files the kit does not hold.
KIT_LACKS = re.compile(r"map file '.*' not found|is not in any catalog directory|"
                       r"catalog file .* not found|catalog '.*' not found")


def causes(text, side):
    lowered = text.lower()
    return {name for name, tester, corsa in CAUSES
            if re.search(tester if side == 0 else corsa, lowered)}


def run_validate(corsa, path, strict=False):
    """Exit code (negative: killed by that signal), the error lines (line, message) and the
    lines of lenient readings (warnings ending in `(read as ...)`)."""
    command = [corsa, 'validate'] + (['--strict'] if strict else []) + [os.path.basename(path)]
    try:
        done = subprocess.run(command, cwd=os.path.dirname(path),
                              capture_output=True, text=True, errors='replace', timeout=120)
    except subprocess.TimeoutExpired:
        return 'timeout', [], set()
    errors = []
    lenient = set()
    for line in done.stderr.splitlines() + done.stdout.splitlines():
        match = DIAGNOSTIC_LINE.match(line)
        if not match or os.path.basename(match['file']) != os.path.basename(path):
            continue
        if match['severity'] == 'error':
            errors.append((int(match['line']), match['message']))
        elif '(read as ' in match['message']:
            lenient.add(int(match['line']))
    return done.returncode, errors, lenient


def match_expected(expected, errors, lenient):
    """Per expected message: 'cause' (an error at its line naming a cause it names), 'line' (an
    error at its line), 'lenient' (no error, but a lenient reading warned about at its line) or
    'missed'; and the errors no expected message's line names."""
    used = set()
    results = []
    for item in expected:
        wanted = causes(item['message'], 0)
        at_line = [i for i, (line, _) in enumerate(errors) if line == item['line']]
        same_cause = [i for i in at_line if causes(errors[i][1], 1) & wanted]
        pick = next((i for i in same_cause if i not in used), None)
        if pick is None and same_cause:
            pick = same_cause[0]  # one Corsa error may name two of the tester's at one place
        kind = 'cause' if pick is not None else None
        if pick is None:
            pick = next((i for i in at_line if i not in used), at_line[0] if at_line else None)
            kind = 'line' if pick is not None else (
                'lenient' if item['line'] in lenient else 'missed')
        if pick is not None:
            used.add(pick)
        results.append((item, kind, errors[pick][1] if pick is not None else ''))
    expected_lines = {item['line'] for item in expected}
    others = [error for error in errors if error[0] not in expected_lines]
    return results, others


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--kit', default=DEFAULT_KIT)
    parser.add_argument('--corsa', default=os.path.join(REPO, 'build', 'corsa'))
    parser.add_argument('--good', nargs='*', default=None,
                        help='folders of files that must load (default ../shared/conformance)')
    parser.add_argument('--no-good', action='store_true')
    parser.add_argument('--strict', action='store_true', help='run `corsa validate --strict`')
    parser.add_argument('-v', '--verbose', action='store_true')
    args = parser.parse_args()

    expected_path = os.path.join(args.kit, 'expected.json')
    if not os.path.isfile(expected_path):
        print(f'skipped: no API tester kit at {args.kit} (expected.json missing)')
        return 0
    with open(expected_path, encoding='utf-8') as f:
        files = json.load(f)['files']

    failures = []
    totals = {'expected': 0, 'cause': 0, 'line': 0, 'lenient': 0, 'missed': 0, 'kit': 0,
              'other': 0}
    for name in sorted(files):
        path = os.path.join(args.kit, name)
        code, errors, lenient = run_validate(args.corsa, path, args.strict)
        if code != 2:
            failures.append(f'{name}: exit {code} (a bad file must exit 2)')
        expected = files[name]
        print(f'{name}: exit {code}, {len(errors)} errors')
        if expected is None:
            for line, message in errors:
                print(f'  (no expectation) {line}: {message}')
            continue
        results, others = match_expected(expected, errors, lenient)
        for item, kind, message in results:
            totals['expected'] += 1
            totals[kind] += 1
            if kind != 'cause' or args.verbose:
                print(f"  {kind:7} {item['line']}: tester '{item['message']}'"
                      + (f" / corsa '{message}'" if message else ''))
        for line, message in others:
            kind = 'kit' if KIT_LACKS.search(message) else 'other'
            totals[kind] += 1
            if kind == 'other' or args.verbose:
                print(f'  corsa-only{" (kit lacks the file)" if kind == "kit" else ""} '
                      f'{line}: {message}')

    good_dirs = [] if args.no_good else args.good
    if good_dirs is None:
        default = os.path.join(os.path.dirname(REPO), 'shared', 'conformance')
        good_dirs = [default] if os.path.isdir(default) else []
    good = 0
    for folder in good_dirs:
        for root, _, names in sorted(os.walk(folder)):
            for name in sorted(names):
                if not name.endswith('.xosc') or 'atalog' in root:
                    continue
                code, errors, _ = run_validate(args.corsa, os.path.join(root, name), args.strict)
                good += 1
                if code != 0:
                    failures.append(f'{os.path.join(root, name)}: exit {code}, '
                                    f'{len(errors)} errors (a good file must exit 0)')

    found = totals['cause'] + totals['line']
    print(f"\nexpected errors: {found} of {totals['expected']} found at their line "
          f"({totals['cause']} naming the same cause, {totals['line']} another), "
          f"{totals['lenient']} read leniently with a located warning (errors under --strict), "
          f"{totals['missed']} missed")
    print(f"Corsa-only errors: {totals['other']} (false positives to read), "
          f"{totals['kit']} about maps or catalogs the kit lacks")
    print(f'good files: {good} checked')
    for failure in failures:
        print(f'FAIL {failure}')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
