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
"""

import argparse
import hashlib
import os
import random
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.path.join(os.path.dirname(REPO), 'shared')
ESMINI = os.environ.get('CORSA_ESMINI_KIT', '/work/notes/esmini')

LOCATED = re.compile(r'^(.+?):(\d+): (error|warning|note): ')
RECORD = re.compile(r'^(.+?): record \d+')
PATH_ERROR = re.compile(r'^(.+?): error: ')
TEMPORARY = re.compile(r'\.tmp(\.|$)|\.corsa\.lock$|\.partial$')

BAD_VALUES = [
    '', ' ', '-1', '-1e300', '1e300', '1e999', '-1e999', 'nan', 'NaN', 'inf', '-inf', '0', '-0',
    '1e-300', '4.9e-324', '18446744073709551617', '-2147483649', '2147483648', 'abc',
    '\u00e9\u4e2d\U0001F600', '\u202e\u0000'.replace('\u0000', ''), '${', '${1/0}', '${$nope + 1}',
    '${(((1}', '${1e308 * 10}', '${-1 % 0}', '${not}', '$', '$$', '${$' + 'x' * 300 + '}',
    '9' * 5000, '0x10', ' 1 ', '1,5', 'true', '\t', '${2 ** 4000}', '${sqrt(-1)}',
]
COUNT_ATTRIBUTES = ('maximumExecutionCount', 'numberOfTestRuns', 'count', 'numberOfPoints',
                    'repetitions', 'channels', 'width', 'height', 'rate', 'pointsPerSecond')
FAMILY_WEIGHTS = {'xosc': 35, 'xodr': 25, 'ngii': 10, 'sweep': 15, 'rig': 15}
MAP_LENGTH_VALUES = ['0', '-1', '-100', '1e300', '1e-300', 'nan', '1e12', '5e-17']


def case_rng(seed, number):
    digest = hashlib.sha256(f'{seed}:{number}'.encode()).digest()
    return random.Random(int.from_bytes(digest[:8], 'little'))


# ---------------------------------------------------------------------------------------------
# XML mutations (ElementTree keeps text and tails, so lines stay roughly where they were)

def elements(root):
    return [e for e in root.iter() if isinstance(e.tag, str)]


def parents(root):
    return {child: parent for parent in root.iter() for child in parent}


def pick_attribute(rng, root, names=None):
    spots = [(e, a) for e in elements(root) for a in e.attrib if names is None or a in names]
    return rng.choice(spots) if spots else (None, None)


def xml_delete(rng, root):
    parent_of = parents(root)
    victims = [e for e in elements(root) if e in parent_of]
    if not victims:
        return 'nothing to delete'
    victim = rng.choice(victims)
    parent_of[victim].remove(victim)
    return f'delete <{victim.tag}>'


def xml_duplicate(rng, root):
    parent_of = parents(root)
    victims = [e for e in elements(root) if e in parent_of]
    if not victims:
        return 'nothing to duplicate'
    victim = rng.choice(victims)
    parent = parent_of[victim]
    copies = rng.choice([1, 1, 2, 50])
    index = list(parent).index(victim)
    for _ in range(copies):
        parent.insert(index, ET.fromstring(ET.tostring(victim)))
    return f'duplicate <{victim.tag}> x{copies}'


def xml_swap(rng, root):
    groups = [p for p in elements(root) if len(p) >= 2]
    if not groups:
        return 'nothing to swap'
    parent = rng.choice(groups)
    i, j = rng.sample(range(len(parent)), 2)
    children = list(parent)
    children[i], children[j] = children[j], children[i]
    for child in list(parent):
        parent.remove(child)
    parent.extend(children)
    return f'swap children {i},{j} of <{parent.tag}>'


def xml_move(rng, root):
    parent_of = parents(root)
    victims = [e for e in elements(root) if e in parent_of]
    if len(victims) < 2:
        return 'nothing to move'
    victim = rng.choice(victims)
    inside = set(victim.iter())
    targets = [e for e in elements(root) if e not in inside]
    target = rng.choice(targets)
    parent_of[victim].remove(victim)
    target.append(victim)
    return f'move <{victim.tag}> into <{target.tag}>'


def xml_nest(rng, root):
    parent_of = parents(root)
    victims = [e for e in elements(root) if e in parent_of]
    if not victims:
        return 'nothing to nest'
    victim = rng.choice(victims)
    depth = rng.choice([30, 99, 101, 257, 900])
    parent = parent_of[victim]
    index = list(parent).index(victim)
    parent.remove(victim)
    outer = ET.Element(victim.tag, victim.attrib)
    inner = outer
    for _ in range(depth - 1):
        nested = ET.SubElement(inner, victim.tag, victim.attrib)
        inner = nested
    inner.extend(list(victim))
    parent.insert(index, outer)
    return f'nest <{victim.tag}> {depth} deep'


def xml_value(rng, root):
    element, attribute = pick_attribute(rng, root)
    if element is None:
        return 'no attribute'
    value = rng.choice(BAD_VALUES)
    element.set(attribute, value)
    return f'<{element.tag} {attribute}="{value[:40]}">'


def xml_drop_attribute(rng, root):
    element, attribute = pick_attribute(rng, root)
    if element is None:
        return 'no attribute'
    del element.attrib[attribute]
    return f'<{element.tag}> without {attribute}'


def xml_huge_count(rng, root):
    element, attribute = pick_attribute(rng, root, COUNT_ATTRIBUTES)
    if element is None:
        return xml_value(rng, root)
    value = rng.choice(['2147483647', '4294967296', '1e18', '-5', '1e9'])
    element.set(attribute, value)
    return f'<{element.tag} {attribute}="{value}">'


def xml_self_parameter(rng, root):
    declarations = [e for e in elements(root) if e.tag == 'ParameterDeclaration' and 'name' in e.attrib]
    if not declarations:
        return xml_value(rng, root)
    first = rng.choice(declarations)
    if len(declarations) >= 2 and rng.random() < 0.5:
        second = rng.choice([d for d in declarations if d is not first])
        first.set('value', '$' + second.get('name'))
        second.set('value', '${$' + first.get('name') + ' + 1}')
        return f'parameters {first.get("name")} and {second.get("name")} name each other'
    first.set('value', '${$' + first.get('name') + ' * 2}')
    return f'parameter {first.get("name")} names itself'


def xml_self_file(rng, root, own_name):
    """A file reference (map, catalog folder, distribution's scenario) pointing at the file itself."""
    spots = [(e, a) for e in elements(root) for a in ('filepath', 'path') if a in e.attrib]
    if not spots:
        return xml_value(rng, root)
    element, attribute = rng.choice(spots)
    element.set(attribute, own_name if attribute == 'filepath' else '.')
    return f'<{element.tag} {attribute}> names the file itself'


XML_MUTATIONS = [xml_delete, xml_duplicate, xml_swap, xml_move, xml_nest, xml_value, xml_value,
                 xml_value, xml_drop_attribute, xml_huge_count, xml_self_parameter]


# OpenDRIVE-specific breakage ------------------------------------------------------------------

def map_geometry_length(rng, root):
    geometries = [e for e in elements(root) if e.tag in ('geometry', 'road') and 'length' in e.attrib]
    if not geometries:
        return 'no geometry'
    value = rng.choice(MAP_LENGTH_VALUES)
    count = 0
    for geometry in geometries:
        if rng.random() < 0.3 or count == 0:
            geometry.set('length', value)
            count += 1
    return f'{count} lengths {value}'


def map_zero_widths(rng, root):
    for width in elements(root):
        if width.tag in ('width', 'border'):
            for attribute in ('a', 'b', 'c', 'd'):
                width.set(attribute, '0')
    return 'every lane 0 m wide'


def map_self_link(rng, root):
    roads = [e for e in elements(root) if e.tag == 'road' and 'id' in e.attrib]
    if not roads:
        return 'no road'
    road = rng.choice(roads)
    link = road.find('link')
    if link is None:
        link = ET.SubElement(road, 'link')
        road.remove(link)
        road.insert(0, link)
    for kind in ('predecessor', 'successor'):
        end = link.find(kind)
        if end is None:
            end = ET.SubElement(link, kind)
        end.attrib.clear()
        end.set('elementType', 'road')
        end.set('elementId', road.get('id'))
        end.set('contactPoint', rng.choice(['start', 'end']))
    return f'road {road.get("id")} linked to itself'


def map_junction_cycle(rng, root):
    connections = [e for e in elements(root) if e.tag == 'connection']
    junctions = [e for e in elements(root) if e.tag == 'junction' and 'id' in e.attrib]
    roads = [e for e in elements(root) if e.tag == 'road' and 'id' in e.attrib]
    if connections and rng.random() < 0.5:
        connection = rng.choice(connections)
        connection.set('incomingRoad', connection.get('connectingRoad', '0'))
        return 'a connection whose incoming road is its connecting road'
    if junctions and roads:
        junction = rng.choice(junctions)
        for road in rng.sample(roads, min(3, len(roads))):
            road.set('junction', junction.get('id'))
            link = road.find('link')
            if link is not None:
                for end in link:
                    end.set('elementType', 'junction')
                    end.set('elementId', junction.get('id'))
        return f'roads in junction {junction.get("id")} linked to it at both ends'
    return map_self_link(rng, root)


def map_lane_self_link(rng, root):
    lanes = [e for e in elements(root) if e.tag == 'lane' and e.get('id') not in (None, '0')]
    if not lanes:
        return 'no lane'
    lane = rng.choice(lanes)
    link = lane.find('link')
    if link is None:
        link = ET.Element('link')
        lane.insert(0, link)
    for kind in ('predecessor', 'successor'):
        end = link.find(kind)
        if end is None:
            end = ET.SubElement(link, kind)
        end.set('id', rng.choice([lane.get('id'), '99', '-2147483648', '']))
    return f'lane {lane.get("id")} linked to itself or nowhere'


HUGE = ['1e300', '-1e300', '1e17', '1e7', '-1e7', '1e-300', '0']


def map_huge_object(rng, root):
    """An object or signal of absurd size, offset or repeat on a random road."""
    roads = [e for e in elements(root) if e.tag == 'road']
    if not roads:
        return 'no road'
    road = rng.choice(roads)
    kind = rng.choice(['crosswalk', 'barrier', 'pole', 'building', 'parkingSpace', 'roadMark',
                       'tree', 'signal'])
    value = rng.choice(HUGE)
    if kind == 'signal':
        holder = road.find('signals')
        if holder is None:
            holder = ET.SubElement(road, 'signals')
        ET.SubElement(holder, 'signal', {
            'id': 'fz', 's': rng.choice(['1', value]), 't': rng.choice(['-4', value]),
            'zOffset': rng.choice(['0', value]), 'orientation': '+', 'dynamic': 'yes',
            'country': 'DE', 'type': '1000001', 'subtype': '-1',
            'height': rng.choice(['1', value]), 'width': rng.choice(['0.5', value])})
        return f'signal with {value}'
    holder = road.find('objects')
    if holder is None:
        holder = ET.Element('objects')
        signals = road.find('signals')
        road.insert(list(road).index(signals) if signals is not None else len(road), holder)
    attributes = {'id': 'fz', 'type': kind, 's': '1', 't': '-4', 'zOffset': '0', 'hdg': '0',
                  'length': '4', 'width': '3', 'height': '2', 'radius': '0.3'}
    attribute = rng.choice(['s', 't', 'zOffset', 'length', 'width', 'height', 'radius', 'hdg'])
    attributes[attribute] = value
    obj = ET.SubElement(holder, 'object', attributes)
    what = f'object {kind} {attribute}={value}'
    if rng.random() < 0.4:
        ET.SubElement(obj, 'repeat', {
            's': '0', 'length': rng.choice(['50', value]), 'distance': rng.choice(['0', '5', value]),
            'tStart': '-4', 'tEnd': rng.choice(['-4', value]), 'heightStart': '1', 'heightEnd': '1',
            'zOffsetStart': '0', 'zOffsetEnd': '0'})
        what += ' repeated'
    elif rng.random() < 0.5:
        outline = ET.SubElement(obj, 'outline')
        for u, v in (('0', '0'), (value, '0'), ('0', rng.choice(['3', value]))):
            ET.SubElement(outline, rng.choice(['cornerLocal', 'cornerRoad']),
                          {'u': u, 'v': v, 'z': '0', 's': u, 't': v, 'dz': '0', 'height': '1'})
        what += ' with an outline'
    return what


def map_huge_profile(rng, root):
    """Elevation, superelevation, lane offset or lane height coefficients of absurd size."""
    spots = [e for e in elements(root)
             if e.tag in ('elevation', 'superelevation', 'laneOffset', 'shape', 'height')]
    value = rng.choice(HUGE)
    if not spots:
        roads = [e for e in elements(root) if e.tag == 'road']
        if not roads:
            return 'no road'
        profile = ET.SubElement(rng.choice(roads), 'elevationProfile')
        spots = [ET.SubElement(profile, 'elevation', {'s': '0', 'a': '0', 'b': '0', 'c': '0', 'd': '0'})]
    spot = rng.choice(spots)
    attribute = rng.choice([a for a in ('a', 'b', 'c', 'd', 'inner', 'outer') if a in spot.attrib] or ['a'])
    spot.set(attribute, value)
    return f'<{spot.tag} {attribute}="{value}">'


MAP_MUTATIONS = [map_huge_object, map_huge_object, map_huge_profile, map_huge_profile, map_geometry_length, map_geometry_length, map_zero_widths, map_self_link,
                 map_junction_cycle, map_lane_self_link]


def mutate_xml(rng, data, own_name, kinds):
    try:
        root = ET.fromstring(data)
    except ET.ParseError:
        return None, 'unparsable source'
    choice = rng.random()
    if kinds == 'xodr' and choice < 0.5:
        what = rng.choice(MAP_MUTATIONS)(rng, root)
    elif choice < 0.07:
        what = xml_self_file(rng, root, own_name)
    else:
        what = rng.choice(XML_MUTATIONS)(rng, root)
    if rng.random() < 0.25:  # a second, unrelated break: every error in one pass
        what += '; ' + rng.choice(XML_MUTATIONS)(rng, root)
    text = ET.tostring(root, encoding='unicode')
    return ('<?xml version="1.0" encoding="UTF-8"?>\n' + text).encode('utf-8'), what


def mutate_bytes(rng, data):
    if not data:
        return data, 'empty'
    if rng.random() < 0.4:
        at = rng.randrange(len(data))
        return data[:at], f'truncated at {at}'
    out = bytearray(data)
    flips = rng.choice([1, 2, 4, 8, 32])
    for _ in range(flips):
        out[rng.randrange(len(out))] = rng.randrange(256)
    return bytes(out), f'{flips} bytes overwritten'


def mutate_text(rng, data, own_name, kinds):
    if rng.random() < 0.2:
        return mutate_bytes(rng, data)
    mutated, what = mutate_xml(rng, data, own_name, kinds)
    if mutated is None:
        return mutate_bytes(rng, data)
    return mutated, what


# NGII layers -----------------------------------------------------------------------------------

def mutate_dbf(rng, data):
    if len(data) < 32 or rng.random() < 0.3:
        return mutate_bytes(rng, data)
    out = bytearray(data)
    records, header, record_size = struct.unpack_from('<IHH', data, 4)
    choice = rng.randrange(4)
    if choice == 0:
        struct.pack_into('<I', out, 4, rng.choice([0, records + 1, 0xFFFFFFFF, records * 1000]))
        return bytes(out), 'record count'
    if choice == 1:
        struct.pack_into('<H', out, 8, rng.choice([0, 1, 32, 0xFFFF, header + 1]))
        return bytes(out), 'header size'
    if choice == 2:
        struct.pack_into('<H', out, 10, rng.choice([0, 1, 0xFFFF, record_size - 1]))
        return bytes(out), 'record size'
    if records == 0 or header + record_size > len(data):
        return mutate_bytes(rng, data)
    record = rng.randrange(records)
    start = header + record * record_size + 1
    length = min(record_size - 1, rng.randrange(1, 24))
    filler = rng.choice([b'9', b'-', b'\xff', b' ', b'N', b'*', b'\x00', b'1e999'])
    text = (filler * length)[:length]
    out[start:start + length] = text
    return bytes(out), f'record {record} fields overwritten with {filler!r}'


def mutate_shape(rng, data, is_index):
    if len(data) < 100 or rng.random() < 0.4:
        return mutate_bytes(rng, data)
    out = bytearray(data)
    choice = rng.randrange(4)
    if choice == 0:
        struct.pack_into('>I', out, 24, rng.choice([0, 50, 0x7FFFFFFF, len(data) // 2 + 1]))
        return bytes(out), 'file length'
    if choice == 1:
        struct.pack_into('<i', out, 32, rng.choice([0, 1, 3, 5, 8, 31, -1, 999]))
        return bytes(out), 'shape type'
    if choice == 2 and not is_index:
        struct.pack_into('>i', out, 104, rng.choice([0, -1, 0x7FFFFFFF, 1]))
        return bytes(out), 'first record length'
    at = 100 + rng.randrange(len(data) - 100) // 8 * 8
    value = rng.choice([float('nan'), float('inf'), -1e308, 1e300, 0.0])
    if at + 8 <= len(data):
        struct.pack_into('<d', out, at, value)
    return bytes(out), f'double at {at} = {value}'


# ---------------------------------------------------------------------------------------------
# The sources and the commands

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


def sources():
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
    xodr = os.path.join(SHARED, 'data', 'xodr')
    if os.path.isdir(xodr):
        maps = [f for f in listing(xodr, '.xodr')
                if os.path.getsize(os.path.join(xodr, f)) < 400_000]
        found.append(Source('xodr', xodr, maps, [
            lambda f, o: ['validate', f],
            lambda f, o: ['map', 'info', f],
            lambda f, o: ['map', 'mesh', f, '-o', os.path.join(o, 'mesh.obj')],
            lambda f, o: ['map', 'mesh', f, '-o', os.path.join(o, 'mesh.ply')],
            lambda f, o: ['map', 'render', f, '-o', os.path.join(o, 'map.png'), '--size', '128'],
            lambda f, o: ['map', 'query', f, '--to-lane', '--in', 'QUERIES'],
            lambda f, o: ['map', 'query', f, '--in', 'QUERIES_ROAD'],
            lambda f, o: ['map', 'holes', f, '--list'],
        ]))
    kcity = os.path.join(SHARED, 'data', 'ngii', 'kcity')
    if os.path.isdir(kcity):
        files = [f for f in listing(kcity, '') if f.endswith(('.dbf', '.shp', '.shx'))]
        found.append(Source('ngii', kcity, files, [
            lambda f, o: ['convert', 'ngii', '.', '-o', os.path.join(o, 'k.xodr'), '--quiet',
                          '--report', os.path.join(o, 'report.csv'),
                          '--placements', os.path.join(o, 'placements.csv')]]))
    scenarios = os.path.join(REPO, 'scenarios')
    found.append(Source('sweep', scenarios, ['suites/sweeps/tiny_grid.xosc'], [
        lambda f, o: ['sweep', f, '-o', os.path.join(o, 'sweep'), '-j', '1', '--quiet',
                      '--duration', '2', '--no-trajectories']]))
    found.append(Source('sweep', scenarios, ['suites/regression/cut_in.xosc', 'cut_in.xosc'], [
        lambda f, o: ['sweep', f, '--param', 'Ego_Speed=20,22', '-o', os.path.join(o, 'sweep'),
                      '-j', '1', '--quiet', '--duration', '2', '--no-trajectories']]))
    if os.path.isdir(conformance):
        distributions = [f for f in listing(conformance, '.xosc')
                         if b'ParameterValueDistribution' in open(os.path.join(conformance, f), 'rb').read()]
        found.append(Source('sweep', conformance, distributions, [
            lambda f, o: ['sweep', f, '-o', os.path.join(o, 'sweep'), '-j', '1', '--quiet',
                          '--duration', '1', '--no-trajectories', '--shard', '0/50']]))
    rig_run = lambda f, o: ['run', 'cut_in.xosc', '--duration', '1', '--quiet', '--threads', '1',
                            '--rig', f, '-o', os.path.join(o, 'dataset')]
    found.append(Source('rig', scenarios, ['rigs/tiny.xml'], [rig_run]))
    # Scenarios broken under a run with the tiny rig (the rig itself intact).
    found.append(Source('xosc', scenarios, ['cut_in.xosc', 'lane_change.xosc', 'overtaking.xosc'], [
        lambda f, o: ['run', f, '--duration', '1', '--quiet', '--threads', '1',
                      '--rig', 'rigs/tiny.xml', '-o', os.path.join(o, 'dataset')]]))
    return found


# ---------------------------------------------------------------------------------------------
# One case

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


def companions(work, path):
    """Files a scenario reads besides itself: its map and catalogs (found by name in the text)."""
    try:
        text = open(path, 'rb').read().decode('utf-8', 'replace')
    except OSError:
        return []
    folder = os.path.dirname(path)
    found = []
    for match in re.finditer(r'(?:filepath|path)="([^"$]+)"', text):
        target = os.path.normpath(os.path.join(folder, match.group(1)))
        if os.path.isfile(target) and target.startswith(work):
            found.append(target)
        elif os.path.isdir(target) and target.startswith(work):
            found.extend(os.path.join(target, n) for n in sorted(os.listdir(target))
                         if n.endswith('.xosc'))
    return found


def break_file(rng, source, work, rel):
    path = os.path.join(work, rel)
    family = source.family
    target = path
    if family in ('xosc', 'sweep') and rng.random() < 0.3:
        others = companions(work, path)
        if others:
            target = rng.choice(others)
    data = open(target, 'rb').read()
    name = os.path.basename(target)
    if family == 'ngii':
        if target.endswith('.dbf'):
            mutated, what = mutate_dbf(rng, data)
        else:
            mutated, what = mutate_shape(rng, data, target.endswith('.shx'))
    else:
        kinds = 'xodr' if target.endswith('.xodr') else 'xosc'
        mutated, what = mutate_text(rng, data, name, kinds)
    with open(target, 'wb') as f:
        f.write(mutated)
    return os.path.relpath(target, work), what


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
