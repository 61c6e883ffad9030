"""corsa.sweep and corsa.test: `corsa sweep` and `corsa test` from Python, their tables as dicts."""

import csv
import os

from . import _corsa
from ._errors import input_error

_INTEGER_COLUMNS = {"index", "exit_status", "steps", "collisions"}
_NUMBER_COLUMNS = {"sim_time", "min_ttc", "min_distance", "max_deceleration", "wall_time"}
_TEXT_COLUMNS = {"status", "end_reason", "error"}


def _number(text):
    """A parameter value as a number when its text is one (OpenSCENARIO spelling), else text."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        return text
    return value if text.strip().lower() not in ("nan", "inf", "-inf", "infinity") else text


def read_summary(path):
    """A sweep's summary.csv as a list of dicts: index, exit_status, steps and collisions as int;
    sim_time and the metrics as float (None when never measured or the variant failed); status,
    end_reason and error as str; parameter values as numbers when they are numbers."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header is None:
            raise input_error(path, "empty summary table")
        rows = []
        for line, row in enumerate(reader, start=2):
            if len(row) != len(header):
                raise input_error(path, f"{len(row)} fields, the header has {len(header)}", line)
            out = {}
            for name, text in zip(header, row):
                if name in _INTEGER_COLUMNS:
                    out[name] = int(text) if text else None
                elif name in _NUMBER_COLUMNS:
                    out[name] = float(text) if text else None
                elif name in _TEXT_COLUMNS:
                    out[name] = text
                else:
                    out[name] = _number(text)
            rows.append(out)
    return rows


def _grid(params):
    axes = []
    for name, values in (params or {}).items():
        if isinstance(values, (list, tuple)):
            text = ",".join(_text(v) for v in values)
        else:
            text = _text(values)
        axes.append(f"{name}={text}")
    return axes


def _text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def sweep(file, params=None, *, output="sweep", jobs=0, shard=None, resume=False, force=False,
          seed=0, dt=0.01, duration=3600.0, record_every=1, trajectories=True, ego=None,
          strict=False):
    """Runs the variants of a ParameterValueDistribution file, or a grid over a scenario's
    parameters, as `corsa sweep` does, and returns summary.csv as a list of dicts (one per
    variant of this shard, by index).

    params   {name: 'LOW:HIGH:STEP' | [values] | value}: grid axes (`--param`), the first varying
             slowest
    output   the sweep folder (`-o`); jobs threads (0: every core); shard 'K/N' or 'auto';
             resume, force, seed, dt, duration, record_every, trajectories, ego, strict as the
             options of `corsa sweep` (docs/sweeps-and-suites.md)

    A variant that fails is a row with status 'error' and its message; a bad plan or output
    folder raises corsa.InputError before anything runs.
    """
    output = os.fspath(output)
    _corsa._sweep(os.fspath(file), _grid(params), output, int(jobs), shard, bool(resume),
                  bool(force), int(seed), float(dt), float(duration), int(record_every),
                  bool(trajectories), ego or "", bool(strict))
    return read_summary(os.path.join(output, "summary.csv"))


def test(suite, *, junit=None, update_goldens=False, jobs=0, output=None):
    """Runs a regression suite as `corsa test` does and returns one dict per test, in the
    suite's order: name, verdict ('PASS', 'FAIL', 'ERROR'), passed, failures (the missed
    expectations), error, golden_written, status, end_reason, sim_time, steps, collisions,
    min_ttc, min_distance, max_deceleration, max_acceleration, max_speed, wall_time.
    junit writes the JUnit report; output keeps each test's trajectory and summary."""
    return _corsa._test(os.fspath(suite), None if junit is None else os.fspath(junit),
                        bool(update_goldens), int(jobs),
                        None if output is None else os.fspath(output))


test.__test__ = False  # not a pytest test function when imported into a test module
