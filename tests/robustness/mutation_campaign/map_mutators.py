"""OpenDRIVE-specific breaks of a map's ElementTree: geometry lengths 0, negative or 1e300, every
lane 0 m wide, roads and lanes linked to themselves, junction cycles, objects, signals and
profiles of absurd size. Each takes (rng, root), changes the tree in place and returns what it
did."""

import xml.etree.ElementTree as ET

from .xml_mutators import elements

MAP_LENGTH_VALUES = ['0', '-1', '-100', '1e300', '1e-300', 'nan', '1e12', '5e-17']


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


MAP_MUTATIONS = [map_huge_object, map_huge_object, map_huge_profile, map_huge_profile,
                 map_geometry_length, map_geometry_length, map_zero_widths, map_self_link,
                 map_junction_cycle, map_lane_self_link]

