#!/usr/bin/env python3
"""Writes a Godot 4 .pck (format 3, as the 4.6 web build's own index.pck) holding the files of a folder.
Usage: mkpck.py DIR OUT.pck. Text project.godot/.tscn/.gd/.gdshader files load at runtime from a pack as they are."""
import hashlib, os, struct, sys

src, out = sys.argv[1], sys.argv[2]
names = sorted(f for f in os.listdir(src) if os.path.isfile(os.path.join(src, f)))
pad = lambda n, a: (n + a - 1) // a * a
BASE = 112  # header: magic, format 3, 4.6.0, flags, file base, directory offset, 16 reserved words; padded
blobs, entries, off = [], [], 0
for n in names:
    data = open(os.path.join(src, n), 'rb').read()
    entries.append((n, off, data))
    blobs.append(data + b'\0' * (pad(len(data), 16) - len(data)))
    off += len(blobs[-1])
directory = struct.pack('<I', len(entries))
for n, o, data in entries:
    p = n.encode()
    p += b'\0' * (pad(len(p), 4) - len(p))
    directory += struct.pack('<I', len(p)) + p + struct.pack('<QQ', o, len(data)) + hashlib.md5(data).digest()
    directory += struct.pack('<I', 0)
PACK_REL_FILEBASE = 2
header = struct.pack('<4s5IQQ', b'GDPC', 3, 4, 6, 0, PACK_REL_FILEBASE, BASE, BASE + off) + b'\0' * 64
with open(out, 'wb') as f:
    f.write(header + b'\0' * (BASE - len(header)))
    f.write(b''.join(blobs))
    f.write(directory)
