#!/usr/bin/env python3

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""A crop of an example scene for tests that bake it under a scheduler:
   crop_scene.py SCENE OUT X0 Z0 SIZE Y0 Y1 [ERODE_CELL]
writes SCENE with its [region] cut to x X0..X0+SIZE, y Y0..Y1, z Z0..Z0+SIZE,
the `eroded` node's cell_size set to ERODE_CELL (default 32 m: the global
pass every worker runs, cheap enough under qemu) and relative paths made
absolute, so OUT can live anywhere. Edits the text (comments and layout
stay) and checks that the result still parses."""
import os
import re
import sys
import tomllib

if len(sys.argv) not in (8, 9):
    sys.exit(__doc__)
src, out = sys.argv[1], sys.argv[2]
x0, z0, size, y0, y1 = map(float, sys.argv[3:8])
erode_cell = float(sys.argv[8]) if len(sys.argv) == 9 else 32.0


def section_sub(text, section, key, value):
    """`key = ...` in [section] set to value (exactly one must be there)."""
    pat = re.compile(r'(^\[' + re.escape(section) + r'\][^\n]*\n(?:(?!^\[)[^\n]*\n)*?)' + key + r' = [^\n#]*', re.M)
    new, n = pat.subn(lambda m: m.group(1) + key + ' = ' + value + ' ', text, count=1)
    if n != 1:
        sys.exit(f"crop_scene.py: no '{key}' in [{section}] of {src}")
    return new


text = open(src).read()
text = section_sub(text, 'region', 'min', f'[{x0}, {y0}, {z0}]')
text = section_sub(text, 'region', 'max', f'[{x0+size}, {y1}, {z0+size}]')
text = section_sub(text, 'terrain.nodes.eroded', 'cell_size', repr(erode_cell))
base = os.path.dirname(os.path.abspath(src))
text = re.sub(r'"(\.\./[^"]*)"', lambda m: '"' + os.path.normpath(os.path.join(base, m.group(1))) + '"', text)
tomllib.loads(text)
open(out, 'w').write(text)
