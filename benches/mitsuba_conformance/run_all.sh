#!/usr/bin/env bash
# Every conformance scene of this folder against its stored Mitsuba
# reference, one `mitsuba_reference.py compare` each, and a summary.
#
#   benches/mitsuba_conformance/run_all.sh PYTHON REFDIR OUTDIR [SPP]
#
# PYTHON: a Python with Mitsuba 3 and numpy (see mitsuba_reference.py);
# REFDIR: the references, NAME.exr + NAME.json per scene NAME.xml, made with
#   PYTHON benches/mitsuba_reference.py reference benches/mitsuba_conformance/NAME.xml \
#       --spp 1024 -o REFDIR/NAME.exr
# OUTDIR: per scene the comparison (NAME.txt) and a side-by-side PNG
# (Mitsuba left). SPP: Candela's samples per pixel, in 8 seeded batches
# (default 256). A scene without a reference is listed as such and makes the
# exit status 1. Prints, per scene, the mean relative 8x8-block error
# against what noise alone gives, and every region's Candela/Mitsuba - 1.
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 PYTHON REFDIR OUTDIR [SPP]" >&2
    exit 2
fi
python=$1
refs=$2
out=$3
spp=${4:-256}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
missing=0
for scene in "$here"/*.xml; do
    name=$(basename "$scene" .xml)
    if [ ! -f "$refs/$name.exr" ]; then
        echo "== $name: no reference $refs/$name.exr"
        missing=$((missing + 1))
        continue
    fi
    "$python" "$here/../mitsuba_reference.py" compare "$refs/$name.exr" --spp "$spp" --batches 8 -t 2 \
        --workdir "$out" --png "$out/$name.png" > "$out/$name.txt"
    echo "== $name"
    grep -E "^mean relative|^  " "$out/$name.txt"
done
if [ "$missing" -gt 0 ]; then
    echo "$missing scene(s) without a reference" >&2
    exit 1
fi
