#!/usr/bin/env bash
# Renders the Shadertoy and plain-GLSL packages of scenes in headless Chromium's WebGL2 (SwiftShader) and compares
# them with `fractal render --backend cpu` of the same view. See README.md.
#
# Usage: tests/engines/webgl/run.sh OUTDIR [SCENE...]
# Environment: FRACTAL (the binary; default target/release/fractal), SIZE (default 480x270), CHROMIUM (default
# /usr/bin/chromium-headless-shell), TOL_MASK_PCT, TOL_MEAN, TOL_OVER8_PCT, TOL_BG_MEAN (see compare.py).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
if [ $# -lt 1 ]; then
    echo "usage: $0 OUTDIR [SCENE...]" >&2
    exit 2
fi
out="$(mkdir -p "$1" && cd "$1" && pwd)"
shift
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
    scenes=(hello_world sphere_box kifs amazing_box mandelbulb)
fi
fractal="${FRACTAL:-$root/target/release/fractal}"
size="${SIZE:-480x270}"
width="${size%x*}"
height="${size#*x}"

[ -x "$fractal" ] || { echo "no fractal binary at $fractal (build it, or set FRACTAL)" >&2; exit 2; }
if [ ! -d "$here/node_modules/playwright-core" ]; then
    (cd "$here" && npm install --no-audit --no-fund --silent)
fi
python3 -c 'import numpy, PIL, OpenEXR' 2>/dev/null || {
    echo "needs python3 with numpy, Pillow and OpenEXR: pip install numpy pillow OpenEXR" >&2
    exit 2
}

start=$(date +%s)
echo "== export ($fractal)"
for s in "${scenes[@]}"; do
    rm -rf "$out/$s"
    mkdir -p "$out/$s"
    for target in shadertoy glsl; do
        "$fractal" export "$s" --target "$target" -o "$out/$s/$target" >>"$out/$s/export.log" 2>&1 \
            || { cat "$out/$s/export.log" >&2; echo "export of $s for $target failed" >&2; exit 1; }
    done
done
python3 "$here/prepare.py" "$out" "$width" "$height" "${scenes[@]}"

echo "== reference: fractal render --backend cpu --samples 1 --size $size --time 0 --aov depth"
for s in "${scenes[@]}"; do
    t0=$(date +%s%N)
    "$fractal" render "$s" --backend cpu --samples 1 --size "$size" --time 0 --aov depth \
        -o "$out/$s/reference.png" >"$out/$s/reference.log" 2>&1 || { cat "$out/$s/reference.log" >&2; }
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    printf '  %s: %d.%01d s\n' "$s" $((ms / 1000)) $((ms % 1000 / 100))
done

echo "== WebGL2 in headless Chromium"
render_rc=0
node "$here/render.mjs" "$out/jobs.json" || render_rc=$?

echo "== compare"
compare_rc=0
python3 "$here/compare.py" "$out" "${scenes[@]}" | tee "$out/table.txt" || compare_rc=$?
echo "total $(( $(date +%s) - start )) s; images in $out/SCENE/{reference,shadertoy,glsl,*.diff}.png"
if [ "$render_rc" -ne 0 ] || [ "$compare_rc" -ne 0 ]; then
    echo "FAILED (render rc $render_rc, compare rc $compare_rc)" >&2
    exit 1
fi
