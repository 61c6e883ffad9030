#!/usr/bin/env python3
"""`corsa validate` on deliberately broken variants of esmini's cut-in.xosc.

Each variant breaks the file in one or more known places (a value of the wrong type, a missing
reference, an unknown element, a road or lane the map lacks, a missing map with 20 errors after
it, truncations, empty and binary files). A variant passes when `corsa validate` exits 2 and
reports an error at exactly the lines broken (every one in one pass, no other), or, for
truncated and unreadable files, exits 2 with a located error; the unbroken file and a harmless
edit must exit 0 with no error. Where Corsa places an error is part of the expectation: an
attribute on a later line of a multi-line tag is reported at the attribute's own line (a
reference to an unknown storyboard element too, at its storyboardElementRef), a parameter whose
declared value is bad also at each use, a catalog entry that does not exist at the
CatalogReference.

The source is esmini's own file (the kit, outside the repository: default /work/notes/esmini);
its map and catalog are named by absolute path. With --valgrind every run is under valgrind's
memcheck, and any report fails the variant.

usage: validate_variants.py [--kit DIR] [--corsa BIN] [--valgrind] [-v]
Exit 0 when every variant passes, 1 otherwise; 0 with a note when the kit is absent.
Python 3, standard library only.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DIAGNOSTIC = re.compile(r'^(.+?):(\d+): (error|warning): (.*)$')
TRUNCATED = 'any'  # expectation of a file that cannot be read: exit 2, a located error

# (line, text, replacement) edits of cut-in.xosc and the lines Corsa reports them at.
SINGLE = {
    'type_double': ((18, 'value="50"', 'value="fifty"'), [18, 48]),
    'type_double_two_dots': ((21, 'value="108"', 'value="1.0.8"'), [21, 57]),
    'lane_id_not_integer': ((48, 'laneId="-3"', 'laneId="-3.5"'), [48]),
    'enum_value': ((55, 'dynamicsShape="step"', 'dynamicsShape="stepped"'), [55]),
    'enum_on_later_line': ((104, 'conditionEdge="none"', 'conditionEdge="sometimes"'), [104]),
    'unknown_entity': ((44, 'entityRef="Ego"', 'entityRef="Egoo"'), [44]),
    'unknown_catalog_entry': ((17, 'value="car_red"', 'value="car_purple"'), [38]),
    'undefined_parameter': ((57, '$EgoSpeed', '$EgoSpeeed'), [57]),
    'unknown_act': ((107, 'storyboardElementRef="CutInAndBrakeAct"',
                     'storyboardElementRef="NoSuchAct"'), [107]),
    'unknown_road': ((48, 'roadId="0"', 'roadId="77"'), [48]),
    'unknown_lane': ((67, 'laneId="-2"', 'laneId="-9"'), [67]),
    'missing_map': ((30, 'e6mini.xodr', 'no_such_map.xodr'), [30]),
    'missing_catalog_folder': ((26, 'Catalogs/Vehicles', 'Catalogs/NoVehicles'), [35, 38]),
    'division_by_zero': ((57, '${$EgoSpeed / 3.6}', '${$EgoSpeed / 0}'), [57]),
    'expression_syntax': ((57, '${$EgoSpeed / 3.6}', '${$EgoSpeed / }'), [57]),
    'unknown_element': ((48, '<LanePosition ', '<LanePositon '), [48]),
}
# 20 errors of the kinds above (the line Corsa reports each at, when not the edited one).
TWENTY = [
    ((18, 'value="50"', 'value="fifty"'), 18), ((21, 'value="108"', 'value="1.0.8"'), 21),
    ((17, 'value="car_red"', 'value="car_purple"'), 38),
    ((44, 'entityRef="Ego"', 'entityRef="Egoo"'), 44),
    ((48, 'laneId="-3"', 'laneId="-3.5"'), 48),
    ((55, 'dynamicsShape="step"', 'dynamicsShape="stepped"'), 55),
    ((57, '$EgoSpeed', '$EgoSpeeed'), 57), ((63, 'entityRef="OverTaker"', 'entityRef="Overtaker"'), 63),
    ((67, 's="25"', 's="abc"'), 67),
    ((79, 'maximumExecutionCount="1"', 'maximumExecutionCount="-1x"'), 79),
    ((81, 'entityRef="$owner"', 'entityRef="$ownr"'), 81),
    ((84, 'priority="overwrite"', 'priority="sometimes"'), 84),
    ((89, 'dynamicsDimension="time"', 'dynamicsDimension="distancee"'), 89),
    ((104, 'conditionEdge="none"', 'conditionEdge="sometimes"'), 104),
    ((107, 'storyboardElementRef="CutInAndBrakeAct"', 'storyboardElementRef="NoSuchAct"'), 107),
    ((119, 'value="3"', 'value="three"'), 119),
    ((121, 'entityRef="Ego"', 'entityRef="Nobody"'), 121),
    ((152, 'value="-4"', 'value="${-4 / 0}"'), 152),
    ((186, 'rule="greaterThan"', 'rule="greater"'), 186),
    ((195, 'delay="5"', 'delay="five"'), 195),
]
MISSING_MAP = (30, 'e6mini.xodr', 'no_such_map.xodr')


def variants(kit):
    """{name: (bytes, expected lines or TRUNCATED)}."""
    resources = os.path.join(kit, 'resources')
    text = open(os.path.join(resources, 'xosc', 'cut-in.xosc'), encoding='utf-8').read()
    for relative in ('../xosc/Catalogs/Vehicles', '../xodr/e6mini.xodr', '../models/e6mini.osgb'):
        text = text.replace(f'"{relative}"', '"' + os.path.join(resources, relative[3:]) + '"')
    lines = text.split('\n')

    def edit(edits):
        edited = list(lines)
        for line, old, new in edits:
            if old not in edited[line - 1]:
                raise SystemExit(f'cut-in.xosc changed: no {old!r} at line {line}')
            edited[line - 1] = edited[line - 1].replace(old, new, 1)
        return '\n'.join(edited).encode()

    out = {'unbroken': (text.encode(), [])}
    for name, (change, at) in SINGLE.items():
        out[name] = (edit([change]), at)
    # The missing map is reported, and so are the 20 errors after it (the lane id, which only
    # the map can judge, then through its bad s parameter).
    out['missing_map_and_20_errors'] = (edit([MISSING_MAP] + [c for c, _ in TWENTY]),
                                        sorted({at for _, at in TWENTY} | {30}))
    # With the map present: 19 of them, the lane id judged against the map in the same pass.
    nineteen = [(c, at) for c, at in TWENTY if c[0] != 18]
    out['map_and_19_errors'] = (edit([c for c, _ in nineteen]), sorted({at for _, at in nineteen}))
    data = text.encode()
    for per_mille in (50, 200, 350, 500, 650, 800, 950, 999):
        out[f'truncated_{per_mille:03d}'] = (data[:len(data) * per_mille // 1000], TRUNCATED)
    seven = edit([c for c, _ in TWENTY[:6]])
    out['truncated_after_errors'] = (seven[:len(seven) * 7 // 10], TRUNCATED)
    out['empty'] = (b'', TRUNCATED)
    out['declaration_only'] = (b'<?xml version="1.0"?>\n', TRUNCATED)
    out['wrong_root'] = (b'<?xml version="1.0"?>\n<OpenDRIVE/>\n', TRUNCATED)
    out['binary'] = (bytes(range(256)) * 4, TRUNCATED)
    # A line break inside a number: XML reads it as a space, which xsd:double collapses.
    cut = data.index(b'value="50"') + 9
    out['line_break_in_number'] = (data[:cut] + b'\n' + data[cut:], [])
    return out


def validate(corsa, folder, name, use_valgrind):
    command = [corsa, 'validate', name + '.xosc']
    if use_valgrind:
        command = ['valgrind', '-q', '--error-exitcode=99', '--leak-check=no'] + command
    done = subprocess.run(command, cwd=folder, capture_output=True, text=True, errors='replace',
                          timeout=600)
    errors = []
    for line in done.stderr.splitlines():
        match = DIAGNOSTIC.match(line)
        if match and match[3] == 'error':
            errors.append((int(match[2]), match[4]))
    valgrind = [line for line in done.stderr.splitlines() if re.match(r'^==\d+==', line)]
    return done.returncode, errors, valgrind


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--kit', default='/work/notes/esmini')
    parser.add_argument('--corsa', default=os.path.join(REPO, 'build', 'corsa'))
    parser.add_argument('--valgrind', action='store_true')
    parser.add_argument('-v', '--verbose', action='store_true')
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.kit, 'resources', 'xosc', 'cut-in.xosc')):
        print(f'skipped: no esmini kit at {args.kit}')
        return 0
    failed = 0
    all_variants = variants(args.kit)
    with tempfile.TemporaryDirectory(prefix='corsa-variants-') as folder:
        for name, (data, expected) in all_variants.items():
            with open(os.path.join(folder, name + '.xosc'), 'wb') as f:
                f.write(data)
            code, errors, valgrind = validate(args.corsa, folder, name, args.valgrind)
            lines = sorted({line for line, _ in errors})
            if expected == TRUNCATED:
                ok = code == 2 and bool(errors)
            elif not expected:
                ok = code == 0 and not errors
            else:
                ok = code == 2 and lines == expected
            ok = ok and not valgrind
            failed += 0 if ok else 1
            print(f"{'ok  ' if ok else 'FAIL'} {name}: exit {code}, errors at {lines}"
                  + ('' if expected == TRUNCATED else f' (expected {expected})'))
            if not ok or args.verbose:
                for line, message in errors:
                    print(f'       {line}: {message[:200]}')
                for line in valgrind[:20]:
                    print(f'       {line}')
    print(f'{len(all_variants) - failed} of {len(all_variants)} variants as expected'
          + (' (under valgrind memcheck)' if args.valgrind else ''))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
