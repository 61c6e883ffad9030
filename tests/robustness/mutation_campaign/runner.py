"""One case of the campaign: its source, file, command and break drawn from (seed, case number)
alone, run under a time and memory limit from a fresh folder, and judged (see campaign.py for
what counts as a finding)."""

import hashlib
import os
import random
import re
import shutil
import signal
import subprocess
import time

from .breaking import break_file
from .sources import prepare_workspace

LOCATED = re.compile(r'^(.+?):(\d+): (error|warning|note): ')
RECORD = re.compile(r'^(.+?): record \d+')
PATH_ERROR = re.compile(r'^(.+?): error: ')
TEMPORARY = re.compile(r'\.tmp(\.|$)|\.corsa\.lock$|\.partial$')

FAMILY_WEIGHTS = {'xosc': 35, 'xodr': 25, 'ngii': 10, 'sweep': 15, 'rig': 15}


def case_rng(seed, number):
    digest = hashlib.sha256(f'{seed}:{number}'.encode()).digest()
    return random.Random(int.from_bytes(digest[:8], 'little'))


def snapshot(root):
    state = {}
    for folder, dirs, names in os.walk(root):
        for name in names + dirs:
            path = os.path.join(folder, name)
            try:
                info = os.lstat(path)
            except OSError:
                continue
            state[os.path.relpath(path, root)] = (info.st_size, info.st_mtime_ns, info.st_mode)
    return state



def run_case(args, number, all_sources, scratch):
    rng = case_rng(args.seed, number)
    families = sorted({s.family for s in all_sources})
    family = rng.choices(families, [FAMILY_WEIGHTS[f] for f in families])[0]
    source = rng.choice([s for s in all_sources if s.family == family])
    rel = rng.choice(source.files)
    command = rng.choice(source.commands)
    case_dir = os.path.join(scratch, f'case{number}')
    work = os.path.join(case_dir, 'in')
    cwd = os.path.join(case_dir, 'cwd')
    out = os.path.join(cwd, 'out')
    prepare_workspace(source, work)
    os.makedirs(out)
    broken, what = break_file(rng, source, work, rel)
    before_in = snapshot(work)
    argv = command(rel, out)
    argv = [os.path.join(work, a) if a.startswith('QUERIES') else a for a in argv]
    # Inputs are named relative to the folder the command runs in (as users do), outputs by
    # absolute path: a scenario, map or distribution from its own folder; rig runs and NGII
    # conversions from the workspace's top (the rig and the scenario sit in different folders).
    if source.family in ('rig', 'ngii') or '--rig' in argv:
        run_dir = work
    else:
        run_dir = os.path.join(work, os.path.dirname(rel))
        argv = [os.path.basename(a) if a == rel else a for a in argv]
    full = ['prlimit', f'--as={args.memory}', args.corsa] + argv
    started = time.monotonic()
    try:
        process = subprocess.Popen(full, cwd=run_dir, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, start_new_session=True)
        stdout, stderr = process.communicate(timeout=args.timeout)
        code = process.returncode
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        stdout, stderr = process.communicate()
        code = 'timeout'
    seconds = time.monotonic() - started
    stderr_text = stderr.decode('utf-8', 'replace')
    problems = judge(code, stderr_text, work, before_in, out, cwd)
    record = {
        'case': number, 'family': source.family, 'file': broken, 'mutation': what,
        'command': ' '.join(['corsa'] + argv), 'folder': os.path.relpath(run_dir, work),
        'exit': code, 'seconds': round(seconds, 2), 'problems': problems,
        'stderr': stderr_text[-2000:],
    }
    if (problems or args.keep) and args.findings:
        keep = os.path.join(args.findings, f'case{number}')
        shutil.rmtree(keep, ignore_errors=True)
        os.makedirs(keep)
        shutil.copy(os.path.join(work, broken), os.path.join(keep, os.path.basename(broken)))
        with open(os.path.join(keep, 'case.txt'), 'w') as f:
            for key, value in record.items():
                f.write(f'{key}: {value}\n')
    shutil.rmtree(case_dir, ignore_errors=True)
    return record


def judge(code, stderr, work, before_in, out, cwd):
    problems = []
    if code == 'timeout':
        problems.append('time limit')
    elif code < 0:
        problems.append(f'signal {-code}')
    elif code not in (0, 1, 2):
        problems.append(f'exit {code}')
    lines = stderr.splitlines()
    located = [l for l in lines if LOCATED.match(l) or RECORD.match(l) or PATH_ERROR.match(l)]
    if code == 2 and not any(': error: ' in l or RECORD.match(l) for l in located):
        problems.append('exit 2 without a located error')
    for line in lines:
        if re.search(r'\berror\b', line, re.IGNORECASE) and line not in located \
                and not line.startswith(('  ', '\t', 'usage')):
            problems.append('unlocated error line: ' + line[:160])
            break
    if code == 'timeout':
        return problems  # a killed run may leave anything
    after_in = snapshot(work)
    if after_in != before_in:
        changed = sorted(k for k in set(after_in) | set(before_in) if after_in.get(k) != before_in.get(k))
        problems.append('input folder changed: ' + ', '.join(changed[:5]))
    stray = sorted(n for n in os.listdir(cwd) if n != 'out')
    if stray:
        problems.append('written into the working folder: ' + ', '.join(stray[:5]))
    left = []
    for folder, dirs, names in os.walk(out):
        for name in names + dirs:
            left.append(os.path.relpath(os.path.join(folder, name), out))
    if code == 2 and left:
        problems.append('exit 2 left output: ' + ', '.join(sorted(left)[:5]))
    # Trajectories and meshes hold numbers only (summaries and sweep tables quote parameter
    # names, which may be 'NaN'): one file named is enough.
    for name in left:
        if os.path.basename(name) in ('traj.csv', 'mesh.obj', 'mesh.ply', 'k.xodr') \
                and not any(p.startswith('non-finite') for p in problems):
            try:
                with open(os.path.join(out, name), 'rb') as f:
                    text = f.read(64 << 20)
            except OSError:
                continue
            if name.endswith('.ply') and b'binary' in text[:200]:
                continue
            if re.search(rb'(?<![A-Za-z_])-?(nan|inf)(?![A-Za-z_])', text, re.IGNORECASE):
                problems.append(f'non-finite number written in {name}')
    temporaries = [n for n in left if TEMPORARY.search(n)]
    if temporaries:
        problems.append('temporaries left: ' + ', '.join(temporaries[:5]))
    return problems
