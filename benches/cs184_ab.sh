#!/usr/bin/env bash
# The CS184 benchmark render with two builds, interleaved: wall and user CPU
# of every run, and the load average before each. On a shared machine only
# side-by-side runs compare; user CPU is the fairer figure under load.
#
#   benches/cs184_ab.sh [-n PAIRS] [-s SPP] A_BINARY B_BINARY [SCENE.dae]
#
# Each pair runs `BIN -q -t 2 -s SPP -l 4 -m 5 -r 480 360 -f OUT.exr SCENE`
# (SPP 64 by default: the CS184 benchmark), A first in odd pairs and B
# first in even ones, then prints the medians and the median of the per-pair
# user-CPU ratios B/A. The images are compared too: two builds that should
# give the same picture must write the same pixels (`candela compare`: MSE
# exactly 0; the files differ anyway, as the header carries the render time).
set -euo pipefail

pairs=3
spp=64
while getopts "n:s:" opt; do
    case $opt in
        n) pairs=$OPTARG ;;
        s) spp=$OPTARG ;;
        *) echo "usage: $0 [-n PAIRS] [-s SPP] A_BINARY B_BINARY [SCENE.dae]" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 2 ]; then
    echo "usage: $0 [-n PAIRS] [-s SPP] A_BINARY B_BINARY [SCENE.dae]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
a=$1
b=$2
scene=${3:-$here/../../shared/scenes/cs184/CBbunny.dae}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() { # name binary pair -> "wall user" on stdout
    local load
    load=$(cut -d' ' -f1 /proc/loadavg)
    /usr/bin/time -f "%e %U" -o "$work/time" "$2" -q -t 2 -s "$spp" -l 4 -m 5 -r 480 360 \
        -f "$work/$1.$3.exr" "$scene"
    read -r wall user < "$work/time"
    echo "pair $3 $1: wall $wall s, user $user s, load $load" >&2
    echo "$wall $user"
}

echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores" >&2
for ((k = 1; k <= pairs; k++)); do
    if ((k % 2 == 1)); then
        ra=$(run A "$a" "$k"); rb=$(run B "$b" "$k")
    else
        rb=$(run B "$b" "$k"); ra=$(run A "$a" "$k")
    fi
    echo "$k $ra $rb" >> "$work/runs"
    report=$("$b" compare --json "$work/B.$k.exr" "$work/A.$k.exr" || true)
    if [[ $report == *'"mse": 0.0,'* ]]; then
        same=identical
    else
        same=DIFFERENT
    fi
    echo "pair $k: images $same" >&2
done
python3 - "$work/runs" <<'EOF'
import statistics, sys
rows = [list(map(float, l.split()[1:])) for l in open(sys.argv[1])]
med = statistics.median
aw, au, bw, bu = (med(r[i] for r in rows) for i in range(4))
ratio = med(r[3] / r[1] for r in rows)
print("| pair | A wall / user (s) | B wall / user (s) | user B/A |")
print("|---:|---|---|---:|")
for k, r in enumerate(rows, 1):
    print(f"| {k} | {r[0]:.1f} / {r[1]:.1f} | {r[2]:.1f} / {r[3]:.1f} | {r[3] / r[1]:.3f} |")
print(f"| median | {aw:.1f} / {au:.1f} | {bw:.1f} / {bu:.1f} | **{ratio:.3f}** |")
EOF
