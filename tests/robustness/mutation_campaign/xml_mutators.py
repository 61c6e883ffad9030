"""Breaks of any XML file, made on its ElementTree (which keeps text and tails, so lines stay
roughly where they were): elements deleted, duplicated, swapped, moved or nested thousands deep;
attribute values made huge, negative, NaN, inf, empty, unicode or bad `${...}` expressions, or
deleted; counts made huge; parameters that name themselves; a file reference naming the file
itself. Each mutation takes (rng, root), changes the tree in place and returns what it did."""

import xml.etree.ElementTree as ET

BAD_VALUES = [
    '', ' ', '-1', '-1e300', '1e300', '1e999', '-1e999', 'nan', 'NaN', 'inf', '-inf', '0', '-0',
    '1e-300', '4.9e-324', '18446744073709551617', '-2147483649', '2147483648', 'abc',
    '\u00e9\u4e2d\U0001F600', '\u202e\u0000'.replace('\u0000', ''), '${', '${1/0}', '${$nope + 1}',
    '${(((1}', '${1e308 * 10}', '${-1 % 0}', '${not}', '$', '$$', '${$' + 'x' * 300 + '}',
    '9' * 5000, '0x10', ' 1 ', '1,5', 'true', '\t', '${2 ** 4000}', '${sqrt(-1)}',
]
COUNT_ATTRIBUTES = ('maximumExecutionCount', 'numberOfTestRuns', 'count', 'numberOfPoints',
                    'repetitions', 'channels', 'width', 'height', 'rate', 'pointsPerSecond')


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

