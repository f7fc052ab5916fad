#!/usr/bin/env bash
# Renders the image sets of the CS184 PathTracer write-up (Parts 3 and 4)
# with candela, into one folder, so they can be compared side by side:
#   - uniform hemisphere sampling vs light sampling (direct lighting)
#   - 1, 4, 16 and 64 light rays per area light at 1 sample per pixel
#   - direct-only vs indirect-only illumination
#   - light after exactly k bounces (-o 0) and up to k bounces, k = 0..5 and 100,
#     and bounces 0..5 as the EXR layers of one render (--bounce-layers 5)
#   - 1 to 1024 samples per pixel
#
# usage: examples/cs184_writeup.sh [OUT_DIR] [WIDTH HEIGHT]
#   defaults: cs184-writeup/ at 480 360 (the course's size); pass e.g.
#   "out 240 180" for a quick look. Needs ../shared/scenes/cs184 beside the
#   repository (or set SCENES=...).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-cs184-writeup}
w=${2:-480}
h=${3:-360}
scenes=${SCENES:-$here/../shared/scenes/cs184}
mkdir -p "$out"
cargo build --release -q --manifest-path "$here/Cargo.toml" -p candela-cli
candela() { "$here/target/release/candela" -q -r "$w" "$h" "$@"; }
bunny=$scenes/CBbunny.dae
spheres=$scenes/CBspheres_lambertian.dae

echo "hemisphere vs light sampling (direct lighting, 16 spp, 8 light rays)"
candela -s 16 -l 8 -m 1 -H -f "$out/bunny_hemisphere.png" "$bunny"
candela -s 16 -l 8 -m 1 --light-only -f "$out/bunny_light_sampling.png" "$bunny"
candela -s 16 -l 8 -m 1 -H -f "$out/spheres_hemisphere.png" "$spheres"
candela -s 16 -l 8 -m 1 --light-only -f "$out/spheres_light_sampling.png" "$spheres"

echo "light rays per area light at 1 spp"
for l in 1 4 16 64; do
  candela -s 1 -l "$l" -m 1 --light-only -f "$out/spheres_l$l.png" "$spheres"
done

echo "direct vs indirect illumination (1024 spp)"
candela -s 1024 -l 1 -m 5 --direct-only -f "$out/bunny_direct.png" "$bunny"
candela -s 1024 -l 1 -m 5 --indirect-only -f "$out/bunny_indirect.png" "$bunny"

echo "bounces: exactly k (-o 0) and up to k (-o 1), 1024 spp"
for m in 0 1 2 3 4 5 100; do
  candela -s 1024 -l 1 -m "$m" -o 0 -f "$out/bunny_only_bounce_$m.png" "$bunny"
  candela -s 1024 -l 1 -m "$m" -o 1 -f "$out/bunny_up_to_bounce_$m.png" "$bunny"
done

echo "bounces 0..5 as the layers bounce_0 ... bounce_5 of one EXR (1024 spp)"
candela -s 1024 -l 1 -m 5 --bounce-layers 5 -f "$out/bunny_bounce_layers.exr" "$bunny"

echo "samples per pixel"
for s in 1 2 4 8 16 64 1024; do
  candela -s "$s" -l 4 -m 5 -f "$out/spheres_s$s.png" "$spheres"
done

echo "wrote $(ls "$out" | wc -l) images to $out"
