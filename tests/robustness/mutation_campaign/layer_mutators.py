"""Byte-level breaks (truncation, bytes overwritten) of any file, and the NGII layers' `.dbf`,
`.shp` and `.shx` broken where their headers and records are: counts, sizes, shape type, field
texts and coordinates overwritten. Each takes the file's bytes and returns (bytes, what)."""

import struct


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

