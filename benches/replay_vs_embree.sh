#!/usr/bin/env bash
# Candela and Embree on the same ray sets in one sitting: interleaved pairs,
# medians. On a shared machine a ratio means something only when both sides
# are measured side by side, several times (../shared/bench/README.md).
#
#   benches/replay_vs_embree.sh [-n PAIRS] [-s SECONDS] [-i ISA] CANDELA[,CANDELA2...] PYTHON MESH.tri RAYS.rays [MESH RAYS ...]
#
# CANDELA: the release binary (target/release/candela), or several
# comma-separated (e.g. a copy of main's build and this one, to measure a
# change against Embree and against the previous build in the same
# sitting); PYTHON: a Python with embreex and numpy (see
# benches/replay_embree.py). For each ray set, PAIRS rounds (default 5) of
# one run of each, the order reversed in every other round (Candela first in
# odd rounds, Embree first in even ones) so a drift in the load hits all alike.
# Each run replays closest and any hit on one thread and reports the fastest
# pass by CPU time (`candela bench rays -t 1`, Embree's batch API, which
# calls its single-ray kernels once per ray). Prints per set the median
# Mrays per CPU-second of each and the median of the per-pair ratios.
# -i ISA caps the kernels Embree picks (its `max_isa`, e.g. avx2 on a CPU with
# AVX-512, for figures comparable with machines without it): the script then
# builds benches/embree_max_isa.c with cc and preloads it into the Embree runs.
set -euo pipefail

pairs=5
seconds=1
isa=
while getopts "n:s:i:" opt; do
    case $opt in
        n) pairs=$OPTARG ;;
        s) seconds=$OPTARG ;;
        i) isa=$OPTARG ;;
        *) echo "usage: $0 [-n PAIRS] [-s SECONDS] [-i ISA] CANDELA PYTHON MESH RAYS [MESH RAYS ...]" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 4 ] || [ $(( ($# - 2) % 2 )) -ne 0 ]; then
    echo "usage: $0 [-n PAIRS] [-s SECONDS] [-i ISA] CANDELA PYTHON MESH RAYS [MESH RAYS ...]" >&2
    exit 2
fi
IFS=, read -r -a candelas <<< "$1"
python=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
log=$(mktemp)
shim_dir=$(mktemp -d)
trap 'rm -rf "$log" "$shim_dir"' EXIT
embree_env=()
if [ -n "$isa" ]; then
    cc -O2 -shared -fPIC -o "$shim_dir/embree_max_isa.so" "$here/embree_max_isa.c" -ldl
    embree_lib=$("$python" -c 'import embreex, glob, os; d = os.path.dirname(os.path.dirname(embreex.__file__)); print((glob.glob(d + "/embreex.libs/libembree4*") + glob.glob(d + "/embreex/libembree4*"))[0])')
    embree_env=(env LD_PRELOAD="$shim_dir/embree_max_isa.so" EMBREE_REAL_LIB="$embree_lib" EMBREE_EXTRA_CONFIG="max_isa=$isa")
fi

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(uname -n), $(lscpu | sed -n 's/^Model name: *//p' | head -1), load: $(cut -d' ' -f1-3 /proc/loadavg)"
for k in "${!candelas[@]}"; do echo "# candela$((k + 1)): ${candelas[$k]}"; done
echo "# embree: $("$python" -c 'import embreex, importlib.metadata as m; print("embreex", m.version("embreex"))'), kernels: ${isa:-its own choice} ($(grep -q ' avx512f' /proc/cpuinfo && echo 'the CPU has AVX-512' || echo 'no AVX-512 on this CPU'))"

run_candela() { # mesh rays pair
    local k
    for k in "${!candelas[@]}"; do
        "${candelas[$k]}" bench rays "$1" "$2" -t 1 --seconds "$seconds" |
            awk -v set="$(basename "$2" .rays)" -v pair="$3" -v who="candela$((k + 1))" \
                '/^  (closest|any) +1 thread/ { for (i = 1; i <= NF; i++) if ($i == "per" && $(i+1) == "CPU-second") print set, pair, who, $1, $(i-1) }'
    done
}
run_embree() { # mesh rays pair
    "${embree_env[@]}" "$python" "$here/replay_embree.py" "$1" "$2" --seconds "$seconds" --single 0 |
        awk -v set="$(basename "$2" .rays)" -v pair="$3" \
            '/embree batch/ { print set, pair, "embree", $3, $6 }'
}

while [ $# -ge 2 ]; do
    mesh=$1
    rays=$2
    shift 2
    for p in $(seq 1 "$pairs"); do
        if [ $((p % 2)) -eq 1 ]; then
            run_candela "$mesh" "$rays" "$p" >> "$log"
            run_embree "$mesh" "$rays" "$p" >> "$log"
        else
            run_embree "$mesh" "$rays" "$p" >> "$log"
            run_candela "$mesh" "$rays" "$p" >> "$log"
        fi
    done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$log" <<'PY'
import collections, statistics, sys
runs = collections.defaultdict(dict)   # (set, mode) -> {(who, pair): rate}
for line in open(sys.argv[1]):
    s, pair, who, mode, rate = line.split()
    runs[(s, mode)][(who, int(pair))] = float(rate)
whos = sorted({w for r in runs.values() for w, _ in r if w != "embree"})
print("Mrays per CPU-second, medians over the rounds; ratio = median of the per-round ratios to Embree")
print(f"{'set':<20} {'query':<8} {'embree':>7} " + " ".join(f"{w:>9} {'ratio':>6}" for w in whos))
for (s, mode), r in runs.items():
    pairs = sorted({p for _, p in r})
    cols = []
    for w in whos:
        x = [r[(w, p)] for p in pairs if (w, p) in r]
        q = [r[(w, p)] / r[("embree", p)] for p in pairs if (w, p) in r and ("embree", p) in r]
        cols.append(f"{statistics.median(x):9.3f} {statistics.median(q):6.2f}")
    e = statistics.median(r[("embree", p)] for p in pairs if ("embree", p) in r)
    print(f"{s:<20} {mode:<8} {e:7.3f} " + " ".join(cols))
for (s, mode), r in runs.items():
    pairs = sorted({p for _, p in r})
    print(f"# {s} {mode}: " + "; ".join(
        w + " " + " ".join(f"{r[(w, p)]:.2f}" for p in pairs if (w, p) in r) for w in ["embree"] + whos))
PY
