"""One file of a case broken: the file the case names or (for scenarios and distributions,
30 %) one it reads, broken XML-aware (xml_mutators, map_mutators for maps) or byte by byte,
and the NGII layers by their record layout (layer_mutators)."""

import os
import re
import xml.etree.ElementTree as ET

from .layer_mutators import mutate_bytes, mutate_dbf, mutate_shape
from .map_mutators import MAP_MUTATIONS
from .xml_mutators import XML_MUTATIONS, xml_self_file


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



def mutate_text(rng, data, own_name, kinds):
    if rng.random() < 0.2:
        return mutate_bytes(rng, data)
    mutated, what = mutate_xml(rng, data, own_name, kinds)
    if mutated is None:
        return mutate_bytes(rng, data)
    return mutated, what


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

