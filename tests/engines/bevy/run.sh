#!/usr/bin/env bash
# The Bevy package in a real Bevy app: tests/engines/bevy/run.sh [SCENE] [OUTDIR]
#
# Exports SCENE (default amazing_box) for Bevy, writes the package README's Rust module into the app, renders the
# scene's own camera view with the project (CPU, one sample a pixel, with its depth) and in Bevy on lavapipe under
# Xvfb (five shots: the fractal, a cube in front of it and one behind it, each alone and with the fractal; and the
# scene's `fractal mesh` imported from its .glb), then checks holes, colour, occlusion and the mesh's silhouette
# (src/check.rs). Needs Xvfb and Mesa's Vulkan driver (`cargo xtask install`), and
# Rust 1.97.1 for Bevy 0.20 (rust-toolchain.toml; rustup fetches it). The first build takes a while.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
scene="${1:-amazing_box}"
out="$(mkdir -p "${2:-$root/target/engines/bevy/$scene}" && cd "${2:-$root/target/engines/bevy/$scene}" && pwd)"
size="${FRACTAL_ENGINE_SIZE:-480x270}"
fractal="${FRACTAL:-$root/target/release/fractal}"
if [ ! -x "$fractal" ]; then
    (cd "$root" && cargo build --release --bin fractal)
fi

# The scene's camera: a static `camera(vec3(eye), vec3(target)).fov(deg)` in its .fractal file.
file="$root/scenes/fractal/$scene.fractal"
camera="$(tr -d '\n' < "$file" | grep -o 'camera(vec3([^)]*), *vec3([^)]*))\(\.fov([^)]*)\)\?' | head -1 || true)"
if [ -z "$camera" ]; then
    echo "$scene: no static camera(vec3(..), vec3(..)) in $file" >&2
    exit 2
fi
numbers=($(echo "$camera" | sed "s/vec3//g" | grep -o -- '-\?[0-9][0-9.e-]*'))
eye="${numbers[0]},${numbers[1]},${numbers[2]}"
target="${numbers[3]},${numbers[4]},${numbers[5]}"
fov="${numbers[6]:-60}"
echo "$scene: eye $eye, target $target, fov $fov, $size"

"$fractal" export "$scene" --target bevy -o "$out/package" > /dev/null
# The README's first Rust block is the material's Rust side.
awk '/^```rust$/ && !done { inside = 1; next } /^```$/ && inside { done = 1; inside = 0 } inside' \
    "$out/package/README.md" > "$here/src/fractal_material.rs"
mkdir -p "$here/assets/shaders"
rm -f "$here/assets/shaders/"*
cp "$out/package/"*.wesl "$here/assets/shaders/"
# The scene's mesh, imported as the last shot.
"$fractal" mesh "$scene" --resolution 128 -o "$here/assets/mesh.glb" 2> /dev/null

"$fractal" render "$scene" --backend cpu --samples 1 --size "$size" --camera-pos "$eye" --camera-target "$target" \
    --fov "$fov" --aov depth -o "$out/reference.png" 2> /dev/null

started=$(date +%s)
(cd "$here" && cargo build --quiet)
echo "build: $(( $(date +%s) - started )) s"

display="${DISPLAY:-}"
if [ -z "$display" ]; then
    display=":$(( 90 + RANDOM % 9 ))"
    Xvfb "$display" -screen 0 1280x800x24 > /dev/null 2>&1 &
    xvfb=$!
    trap 'kill $xvfb 2> /dev/null || true' EXIT
    sleep 1
fi
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
started=$(date +%s)
(cd "$here" && DISPLAY="$display" WGPU_BACKEND=vulkan RUST_LOG="${RUST_LOG:-error}" cargo run --quiet -- render --eye "$eye" --target "$target" \
    --fov "$fov" --size "$size" --depth "$out/reference.depth.exr" --glb mesh.glb --out "$out")
echo "render: $(( $(date +%s) - started )) s"
(cd "$here" && cargo run --quiet -- check --out "$out" --reference "$out/reference.png" --depth "$out/reference.depth.exr")
