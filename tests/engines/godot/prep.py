#!/usr/bin/env python3
"""Makes the Godot project for one package: prep.py PACKAGE_DIR SCENE OUT_DIR POS TARGET FOV
POS/TARGET: "x,y,z" in the scene's (left-handed, y-up) coordinates. Copies project/ and the package's
SCENE.gdshader(inc) into OUT_DIR, writes config.json (camera, the bound, the cubes) and packs OUT_DIR/game.pck."""
import json, math, os, re, shutil, subprocess, sys

pkg, scene, out, pos, target, fov = sys.argv[1:7]
here = os.path.dirname(os.path.abspath(__file__))
src = os.path.join(out, 'src')
os.makedirs(src, exist_ok=True)
for f in os.listdir(os.path.join(here, 'project')):
    shutil.copy(os.path.join(here, 'project', f), src)
inc = open(os.path.join(pkg, scene + '.gdshaderinc')).read()
shader = open(os.path.join(pkg, scene + '.gdshader')).read()

# The shots compare with the project's render at t = 0: Godot's TIME (which runs from the engine's start) is held at 0
# in the copy of the include.
held = re.sub(r'\bTIME\b', '0.0', inc)
open(os.path.join(src, scene + '.gdshaderinc'), 'w').write(held)
open(os.path.join(src, scene + '.gdshader'), 'w').write(shader)

def vec(name):
    m = re.search(name + r'\s*=\s*vec3\(([^)]*)\)', inc)
    if not m:
        sys.exit(f'prep.py: {name} not found in {scene}.gdshaderinc')
    return [float(x) for x in m.group(1).split(',')]
lo, hi = vec('SDF_BOUND_MIN'), vec('SDF_BOUND_MAX')
p = [float(x) for x in pos.split(',')]
t = [float(x) for x in target.split(',')]
centre = [(a + b) / 2 for a, b in zip(lo, hi)]
R = math.dist(lo, hi) / 2                 # the bound's sphere
D = math.dist(p, centre)                  # camera to the bound's centre
near, far = D - R, D + R
if near <= 0.2:
    # The camera is inside the bound's sphere (not always inside the box): the fractal is at least a little way off.
    near = 0.5 * D
tan = math.tan(math.radians(float(fov)) / 2)
# Cubes are placed in the camera's frame (x right, y up, looking down -z): offset is in units of distance·tan(fov/2).
front_d = 0.6 * near
front = {'dist': front_d, 'size': 0.5 * front_d * tan, 'offset': [0.15, -0.2]}
back_s = 0.8 * far * tan
back = {'dist': far + back_s, 'size': back_s, 'offset': [0.55, 0.45]}
cfg = {'shader': scene + '.gdshader', 'camera_pos': p, 'camera_target': t, 'fov': float(fov),
       'bound_min': lo, 'bound_max': hi, 'probe': [0.5, 0.2, 0.8], 'cube_front': front, 'cube_back': back,
       'far': 2 * (far + 2 * back_s)}
json.dump(cfg, open(os.path.join(src, 'config.json'), 'w'), indent=1)
subprocess.run([sys.executable, os.path.join(here, 'mkpck.py'), src, os.path.join(out, 'game.pck')], check=True)
