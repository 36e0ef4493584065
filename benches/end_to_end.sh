#!/usr/bin/env bash
# The end-to-end figures of docs/performance.md ("End to end: the frame around the kernel", "The viewer's frame",
# and the OpenCL/wgpu kernel ratio per scene) in one run, for a machine with a GPU: it builds nothing and prints
# every figure. Build the binary first (`cargo build --release --features opencl --bin fractal`) and copy it over.
#
#   benches/end_to_end.sh [path/to/fractal] [output folder]
#
# SIZE (default 1920x1080) and FRAMES (default 300, the frames of each sequence and headless viewer run) shrink it
# for a quick check of the script itself.
# Every bench record is appended to OUT/bench.jsonl; sequences are written under OUT and timed.
set -uo pipefail
FRACTAL=${1:-target/release/fractal}
OUT=${2:-end_to_end}
SIZE=${SIZE:-1920x1080}
FRAMES=${FRAMES:-300}
mkdir -p "$OUT"
say() { printf '\n== %s\n' "$*"; }

say "devices"
"$FRACTAL" bench hello_world --backend wgpu --frames 1 --size 64x64 2>&1 | grep -m1 -i "wgpu on"
"$FRACTAL" bench hello_world --backend opencl --frames 1 --size 64x64 2>&1 | grep -m1 -i "opencl on"

say "1. the frame at $SIZE: kernel and frame, generated against the baseline"
for backend in wgpu opencl; do
    echo "-- $backend"
    "$FRACTAL" bench mandelbulb_bench --backend "$backend" --size "$SIZE" --frames 30 --baseline --json "$OUT/bench.jsonl" 2>&1 |
        grep -E "^bench|^\s+(kernel|frame)\s|generated/baseline"
done
for scene in hello_world sierpinski_collection mandelbulb; do
    "$FRACTAL" bench "$scene" --backend wgpu --size "$SIZE" --frames 30 --json "$OUT/bench.jsonl" 2>&1 | grep -E "^bench|^\s+(kernel|frame)\s"
done

say "2. sequences at $SIZE to PNG (frames/s on the last line of each)"
for scene in mandelbulb_bench mandelbulb; do
    rm -rf "${OUT:?}/$scene"
    started=$(date +%s%N)
    last=$("$FRACTAL" render "$scene" --backend wgpu --size "$SIZE" --frames "0..$FRAMES" -o "$OUT/$scene/%05d.png" 2>&1 |
        tail -n 1)
    echo "$scene, $FRAMES frames: $(( ($(date +%s%N) - started) / 1000000 )) ms wall; $last"
done
echo "cores: $(nproc)"

say "3. the viewer's frame at $SIZE, no window"
for present in gpu host; do
    "$FRACTAL" view mandelbulb_bench --headless --frames "$FRAMES" --size "$SIZE" --no-accumulate --present "$present" 2>&1 |
        grep -vE "^(using|viewing|precision)"
done

say "4. OpenCL against wgpu, every scene at $SIZE (kernel medians)"
for scene in $("$FRACTAL" list | awk '{print $1}'); do
    for backend in wgpu opencl; do
        kernel=$("$FRACTAL" bench "$scene" --backend "$backend" --size "$SIZE" --frames 10 --json "$OUT/bench.jsonl" 2>&1 |
            awk '$1 == "kernel" && NF >= 5 {print $3}')
        printf '%-24s %-7s kernel median %s ms\n' "$scene" "$backend" "${kernel:-?}"
    done
done
