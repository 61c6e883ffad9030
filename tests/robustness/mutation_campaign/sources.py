"""What each reader's cases are made from: a source folder copied into the case's workspace, the
files in it a case may break, and the commands that read them (per family: xosc, xodr, ngii,
sweep, rig)."""

import os
import shutil

# The repository (this file is tests/robustness/mutation_campaign/sources.py).
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))
SHARED = os.path.join(os.path.dirname(REPO), 'shared')
ESMINI = os.environ.get('CORSA_ESMINI_KIT', '/work/notes/esmini')


class Source:
    def __init__(self, family, root, files, commands):
        self.family = family      # 'xosc', 'xodr', 'ngii', 'sweep', 'rig'
        self.root = root          # folder copied into the workspace
        self.files = files        # paths relative to root the cases pick from
        self.commands = commands  # list of callables (rel_path, out) -> argv tail


def listing(root, suffix):
    found = []
    for folder, _, names in os.walk(root):
        for name in sorted(names):
            if name.endswith(suffix):
                found.append(os.path.relpath(os.path.join(folder, name), root))
    return sorted(found)


TINY_RIG = '''<?xml version="1.0" encoding="UTF-8"?>
<SensorRig version="1" name="tiny">
  <RgbCamera name="front_rgb" entity="Ego" rate="5" width="64" height="36" fov="90">
    <Mount x="1.6" y="0" z="1.45"/>
  </RgbCamera>
  <Lidar name="roof_lidar" entity="Ego" rate="5" channels="4" range="60"
         pointsPerSecond="4000" rotationFrequency="5" upperFov="5" lowerFov="-15">
    <Mount x="1.0" y="0" z="1.9"/>
  </Lidar>
</SensorRig>
'''

TINY_GRID = '''<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2026-01-01T00:00:00" description="4 variants" author="Corsa"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath="../regression/cut_in.xosc"/>
    <Deterministic>
      <DeterministicSingleParameterDistribution parameterName="Ego_Speed">
        <DistributionRange stepWidth="2">
          <Range lowerLimit="20" upperLimit="22"/>
        </DistributionRange>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="Cut_Speed">
        <DistributionSet>
          <Element value="10"/>
          <Element value="12"/>
        </DistributionSet>
      </DeterministicSingleParameterDistribution>
    </Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
'''


def xosc_sources():
    """Scenarios (or, 30 %, a map or catalog they name): the esmini kit's and the conformance
    files validated and run, and Corsa's own scenarios run with the tiny rig (the rig intact)."""
    found = []
    run = lambda f, o: ['run', f, '--duration', '5', '--quiet', '--threads', '1',
                        '--record', os.path.join(o, 'traj.csv'),
                        '--summary', os.path.join(o, 'summary.json'),
                        '--log', os.path.join(o, 'log.csv')]
    validate = lambda f, o: ['validate', f]
    xosc_commands = [validate, validate, run, run]
    kit = os.path.join(ESMINI, 'resources')
    if os.path.isdir(os.path.join(kit, 'xosc')):
        files = [os.path.join('xosc', f) for f in os.listdir(os.path.join(kit, 'xosc'))
                 if f.endswith('.xosc')]
        found.append(Source('xosc', kit, sorted(files), xosc_commands))
    conformance = os.path.join(SHARED, 'conformance')
    if os.path.isdir(conformance):
        files = [f for f in listing(conformance, '.xosc') if 'Catalogs' not in f]
        found.append(Source('xosc', conformance, files, xosc_commands))
    scenarios = os.path.join(REPO, 'scenarios')
    found.append(Source('xosc', scenarios, ['cut_in.xosc', 'lane_change.xosc', 'overtaking.xosc'], [
        lambda f, o: ['run', f, '--duration', '1', '--quiet', '--threads', '1',
                      '--rig', 'rigs/tiny.xml', '-o', os.path.join(o, 'dataset')]]))
    return found


def xodr_sources():
    """The maps under 400 KB: validated, described, meshed, rendered, queried, searched for holes."""
    xodr = os.path.join(SHARED, 'data', 'xodr')
    if not os.path.isdir(xodr):
        return []
    maps = [f for f in listing(xodr, '.xodr')
            if os.path.getsize(os.path.join(xodr, f)) < 400_000]
    return [Source('xodr', xodr, maps, [
        lambda f, o: ['validate', f],
        lambda f, o: ['map', 'info', f],
        lambda f, o: ['map', 'mesh', f, '-o', os.path.join(o, 'mesh.obj')],
        lambda f, o: ['map', 'mesh', f, '-o', os.path.join(o, 'mesh.ply')],
        lambda f, o: ['map', 'render', f, '-o', os.path.join(o, 'map.png'), '--size', '128'],
        lambda f, o: ['map', 'query', f, '--to-lane', '--in', 'QUERIES'],
        lambda f, o: ['map', 'query', f, '--in', 'QUERIES_ROAD'],
        lambda f, o: ['map', 'holes', f, '--list'],
    ])]


def ngii_sources():
    """K-City's layers, converted with a report and placements."""
    kcity = os.path.join(SHARED, 'data', 'ngii', 'kcity')
    if not os.path.isdir(kcity):
        return []
    files = [f for f in listing(kcity, '') if f.endswith(('.dbf', '.shp', '.shx'))]
    return [Source('ngii', kcity, files, [
        lambda f, o: ['convert', 'ngii', '.', '-o', os.path.join(o, 'k.xodr'), '--quiet',
                      '--report', os.path.join(o, 'report.csv'),
                      '--placements', os.path.join(o, 'placements.csv')]])]


def sweep_sources():
    """A 4-variant grid, `cut_in.xosc` with `--param`, and the conformance distributions (one
    shard of 50)."""
    found = []
    scenarios = os.path.join(REPO, 'scenarios')
    found.append(Source('sweep', scenarios, ['suites/sweeps/tiny_grid.xosc'], [
        lambda f, o: ['sweep', f, '-o', os.path.join(o, 'sweep'), '-j', '1', '--quiet',
                      '--duration', '2', '--no-trajectories']]))
    found.append(Source('sweep', scenarios, ['suites/regression/cut_in.xosc', 'cut_in.xosc'], [
        lambda f, o: ['sweep', f, '--param', 'Ego_Speed=20,22', '-o', os.path.join(o, 'sweep'),
                      '-j', '1', '--quiet', '--duration', '2', '--no-trajectories']]))
    conformance = os.path.join(SHARED, 'conformance')
    if os.path.isdir(conformance):
        distributions = [f for f in listing(conformance, '.xosc')
                         if b'ParameterValueDistribution' in open(os.path.join(conformance, f), 'rb').read()]
        found.append(Source('sweep', conformance, distributions, [
            lambda f, o: ['sweep', f, '-o', os.path.join(o, 'sweep'), '-j', '1', '--quiet',
                          '--duration', '1', '--no-trajectories', '--shard', '0/50']]))
    return found


def rig_sources():
    """The tiny rig, run on `cut_in.xosc` into a dataset."""
    scenarios = os.path.join(REPO, 'scenarios')
    rig_run = lambda f, o: ['run', 'cut_in.xosc', '--duration', '1', '--quiet', '--threads', '1',
                            '--rig', f, '-o', os.path.join(o, 'dataset')]
    return [Source('rig', scenarios, ['rigs/tiny.xml'], [rig_run])]


def sources():
    """Every reader's sources; a case draws its family by weight, then one of that family's
    sources (in the order listed here), a file and a command."""
    return xosc_sources() + xodr_sources() + ngii_sources() + sweep_sources() + rig_sources()


def prepare_workspace(source, work):
    shutil.copytree(source.root, work, symlinks=True,
                    ignore=shutil.ignore_patterns('*.png', '*.jpg', '*.glb', '*.gltf', '*.fbx', '*.osgb'))
    with open(os.path.join(work, 'QUERIES'), 'w') as f:
        f.write('0,0\n10,-3\n1e300,1e300\nnan,1\n-5,2,0\n')
    with open(os.path.join(work, 'QUERIES_ROAD'), 'w') as f:
        f.write('0,0,0\n1,5,-1\n0,1e300,0\n0,-1,nan\n')
    if source.family in ('rig', 'xosc') and os.path.isdir(os.path.join(work, 'rigs')):
        with open(os.path.join(work, 'rigs', 'tiny.xml'), 'w') as f:
            f.write(TINY_RIG)
    if source.family == 'sweep' and os.path.isdir(os.path.join(work, 'suites', 'sweeps')):
        with open(os.path.join(work, 'suites', 'sweeps', 'tiny_grid.xosc'), 'w') as f:
            f.write(TINY_GRID)
