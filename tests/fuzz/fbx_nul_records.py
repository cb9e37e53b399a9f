#!/usr/bin/env python3
"""Writes a binary FBX 7.x whose nested node lists lack the NUL record that assimp's reader
requires again, with that record (25 bytes; 13 before FBX 7.5) after every nested list.

assimp 5.2.5's exporter (`assimp export quads.obj quads_fbx.fbx -ffbx`) omits the record, and its
own reader then refuses the file ("FBX-Tokenize ... block offset is out of range"): as a fuzz seed
it reaches only the tokenizer's errors. The seed tests/fuzz/seeds/mesh/fbx/quads_fbx_records.fbx
was written by

    tests/fuzz/fbx_nul_records.py tests/fuzz/seeds/mesh/fbx/quads_fbx.fbx \\
        tests/fuzz/seeds/mesh/fbx/quads_fbx_records.fbx
"""
import struct
import sys


def main(source, target):
    data = open(source, 'rb').read()
    version = struct.unpack('<I', data[23:27])[0]
    word, record = ('<Q', 25) if version >= 7500 else ('<I', 13)
    size = struct.calcsize(word)

    def nodes(cursor, end, top):
        """The nodes from `cursor` to `end`: (name, property count, properties, nested nodes)."""
        found = []
        while cursor < end:
            end_offset = struct.unpack(word, data[cursor:cursor + size])[0]
            if end_offset == 0:  # a NUL record: the end of the file's nodes, or one already there
                if top:
                    break
                cursor += record
                continue
            count, length = struct.unpack(word[0] + 2 * word[1], data[cursor + size:cursor + 3 * size])
            name_length = data[cursor + 3 * size]
            name_end = cursor + 3 * size + 1 + name_length
            properties = data[name_end:name_end + length]
            nested = nodes(name_end + length, end_offset, False) if name_end + length < end_offset else []
            found.append((data[cursor + 3 * size + 1:name_end], count, properties, nested))
            cursor = end_offset
        return found

    out = bytearray(data[:27])

    def write(node):
        name, count, properties, nested = node
        start = len(out)
        out.extend(bytes(3 * size))
        out.append(len(name))
        out.extend(name + properties)
        if nested:
            for child in nested:
                write(child)
            out.extend(bytes(record))
        struct.pack_into(word[0] + 3 * word[1], out, start, len(out), count, len(properties))

    for node in nodes(27, len(data), True):
        write(node)
    out.extend(bytes(record))
    open(target, 'wb').write(bytes(out))


if __name__ == '__main__':
    main(sys.argv[1], sys.argv[2])
