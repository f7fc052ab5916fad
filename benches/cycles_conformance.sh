#!/usr/bin/env bash
# glTF scenes rendered by Candela and by Blender Cycles, an independent path
# tracer that reads glTF, compared region by region (see BENCHMARKS.md,
# "glTF against Blender Cycles").
#
#   benches/cycles_conformance.sh CANDELA_BINARY [SPP] [WORKDIR]
#
# Sets up a Python environment with Blender as a module (`bpy`, about 370 MB)
# and `OpenEXR` in $CYCLES_VENV (default /tmp/cycles-venv) on first use, then:
#  1. an angle sweep on one plane (benches/cycles/plane_scene.py): a Lambertian
#     plane must agree exactly (its radiance is also printed analytically); the
#     rough dielectric and the clear coat show the two material models apart;
#  2. the conformance scene (benches/cycles/make_scene.py: a sphere per
#     material, every glTF light kind), built and exported by Blender, rendered
#     by both at SPP samples (default 256), with per-material ratios and a
#     side-by-side image WORKDIR/side.png (the two renders, 4× their difference).
# Cycles runs with its biasing shortcuts off (benches/cycles/render_cycles.py).
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 CANDELA_BINARY [SPP] [WORKDIR]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
candela=$(realpath "$1")
spp=${2:-256}
work=${3:-$(mktemp -d)}
mkdir -p "$work"
venv=${CYCLES_VENV:-/tmp/cycles-venv}
if ! "$venv/bin/python" -c "import bpy, OpenEXR" 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q 'bpy>=5.0,<5.1' OpenEXR
fi
py="$venv/bin/python"
quiet() { "$@" > "$work/last.log" 2>&1 || { cat "$work/last.log" >&2; exit 1; }; }
mean() { "$py" -c "import OpenEXR,sys; print(OpenEXR.File(sys.argv[1]).channels()['RGB'].pixels.mean())" "$1"; }

echo "## plane sweep: radiance (mean of 16x16 px), $spp spp"
echo "| elevation | specular | roughness | coat | metallic | Candela | Cycles | Candela / Cycles | Lambert, analytic |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for case in "0 1 0 0" "1 1 0 0" "1 0.5 0 0" "1 1 1 0" "1 1 0 1" "1 0.5 0 1"; do
    read -r spec rough coat metal <<< "$case"
    for elev in 90 45 20; do
        python3 "$here/cycles/plane_scene.py" "$work/plane.gltf" "$elev" "$spec" "$rough" "$coat" 0.5 "$metal"
        quiet "$py" "$here/cycles/render_cycles.py" "$work/plane.gltf" "$work/plane_cycles.exr" 16 16 "$spp"
        quiet "$candela" -q -s "$spp" -m 64 -r 16 16 -f "$work/plane_candela.exr" "$work/plane.gltf"
        a=$(mean "$work/plane_candela.exr")
        b=$(mean "$work/plane_cycles.exr")
        lambert=$([ "$spec" = 0 ] && [ "$coat" = 0 ] && [ "$metal" = 0 ] && python3 -c "import math; print(f'{0.5 / math.pi * 0.8 / math.sqrt(0.77):.5f}')" || echo "")
        python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); print(f'| {sys.argv[3]}° | {sys.argv[4]} | {sys.argv[5]} | {sys.argv[6]} | {sys.argv[7]} | {a:.5f} | {b:.5f} | {a / b:.3f} | {sys.argv[8]} |')" \
            "$a" "$b" "$elev" "$spec" "$rough" "$coat" "$metal" "$lambert"
    done
done

echo
echo "## conformance scene, 480x240, $spp spp"
quiet "$py" "$here/cycles/make_scene.py" "$work/scene.glb"
quiet "$py" "$here/cycles/render_cycles.py" "$work/scene.glb" "$work/cycles.exr" 480 240 "$spp"
quiet "$candela" -q -s "$spp" -m 64 -r 480 240 -f "$work/candela.exr" "$work/scene.glb"
"$py" "$here/cycles/compare.py" "$work/candela.exr" "$work/cycles.exr" "$work/side.png" \
    "$work/scene.glb.regions.json" 2> /dev/null | grep -v "INFO\|^[0-9:.]* *[a-z]* *|"
echo "side by side: $work/side.png"
