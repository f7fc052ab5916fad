#!/usr/bin/env bash
# Instruction counts of a small CS184-style render under callgrind, split by
# where the instructions go. Deterministic, so it compares builds on a
# loaded machine where times do not (cache misses are not in the counts).
#
#   benches/callgrind_render.sh BINARY [OUT.callgrind] [SCENE.dae]
#
# Renders `-q -t 1 -s 8 -l 4 -m 5 -r 120 90` (the benchmark's settings at a
# sixteenth of its pixels and an eighth of its samples; one thread, so the
# counts do not depend on scheduling) and prints the total and the
# inclusive counts of the render loop, the closest-hit and shadow queries,
# light sampling and the sampler (see BENCHMARKS.md for what each covers).
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BINARY [OUT.callgrind] [SCENE.dae]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
bin=$1
out=${2:-$(mktemp --suffix=.callgrind)}
scene=${3:-$here/../../shared/scenes/cs184/CBbunny.dae}
img=$(mktemp --suffix=.exr)
trap 'rm -f "$img"' EXIT
valgrind --tool=callgrind --dump-instr=no --callgrind-out-file="$out" \
    "$bin" -q -t 1 -s 8 -l 4 -m 5 -r 120 90 -f "$img" "$scene" 2> "$out.log"
echo "callgrind data: $out"
python3 - "$out" <<'EOF'
import re, subprocess, sys
def annotate(*flags):
    return subprocess.run(["callgrind_annotate", "--threshold=100", *flags, sys.argv[1]],
                          capture_output=True, text=True, check=True).stdout
def rows(text):
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+(\S+?):(.*)", line)
        if m:
            yield int(m.group(1).replace(",", "")), m.group(2), re.sub(r"\s*\[.*\]$", "", m.group(3))
incl = list(rows(annotate("--inclusive=yes")))
self_ = list(rows(annotate()))
total = int(re.search(r"([\d,]+) \(100.0%\)\s+PROGRAM TOTALS", annotate()).group(1).replace(",", ""))
def inclusive(fn):
    return max((n for n, _, f in incl if f.strip() == fn), default=0)
render = inclusive("rayon::iter::plumbing::bridge_producer_consumer::helper")
visibility = "candela_render::scene::visibility::<impl candela_render::scene::Scene>::"
shadow = inclusive(visibility + "occluded_visible")
# intersect_visible is inlined into its callers: without cut-outs it is
# Scene::intersect (the walk and the hit's surface set-up).
closest = inclusive(visibility + "intersect_visible") or inclusive("candela_render::scene::Scene::intersect")
light = inclusive("candela_render::integrator::direct::Vertex::light_sample") - shadow \
    + inclusive("candela_render::light::area::AreaLight::sample_li_with_area")
# The draws where they are calls of their own, and what is inlined into the
# loop (the rayon helper or, with more inlined, the tile closure).
sampler = inclusive("candela_render::sampling::sampler::Sampler::next_1d") \
    + inclusive("candela_render::sampling::sampler::Sampler::next_2d") \
    + sum(n for n, file, f in self_ if ("helper" in f or "call_mut" in f) and (
        file.endswith(("sampling/hash.rs", "sampling/sobol.rs", "sampling/sampler.rs", "num/uint_macros.rs"))))
print(f"total instructions: {total:,}")
print(f"render loop: {render:,} (100%)")
for name, n in [("shadow-ray queries (any hit)", shadow), ("closest-hit queries + surface set-up", closest),
                ("light sampling, less its shadow queries", light), ("sampler (hashes, scrambles, bit reversal)", sampler),
                ("the rest (path loop, BSDFs, shading frames, film)", render - shadow - closest - light - sampler)]:
    print(f"  {name}: {n:,} ({100 * n / render:.1f}%)")
EOF
