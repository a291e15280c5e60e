#!/usr/bin/env bash
# Whole-program benchmarks: clpc against the floor program (bench/floor.cpp, "as fast as
# reading the file") on generated CL files, with wall time, MB/s and peak RSS from
# /usr/bin/time. Run from the repository root after a build (cmake --build build):
#
#   bash bench/run.sh ratio     200 MB mixed files of both generators (bench/gen_cl, NX-style; bench/gen_apt,
#                               Creo-style) to haas-umc750: clpc (--no-verify and certified) / floor,
#                               medians of 5 alternating runs
#   bash bench/run.sh jobs      eight 25 MB files in one command: -j 2 against -j 1 (certified)
#   bash bench/run.sh rss       1 GB mixed file, operations of at most 20 MB, certified: peak RSS (under 128 MB)
#   bash bench/run.sh linear    10, 100 and 1000 MB: time per MB stays flat
#   bash bench/run.sh all       all four
#
# Files go to $BENCH_DIR (default /tmp/clpc-bench), made once by the generators (deterministic:
# seed 1) and kept for the next run. RUNS=n changes the number of runs.
set -euo pipefail

build=${BUILD_DIR:-build}
dir=${BENCH_DIR:-/tmp/clpc-bench}
runs=${RUNS:-5}
clpc=$build/clpc
floor=$build/bench/floor
gen=$build/bench/gen_cl
gen_apt=$build/bench/gen_apt
machine=${MACHINE:-haas-umc750}
for b in "$clpc" "$floor" "$gen" "$gen_apt"; do
  [[ -x $b ]] || { echo "bench: $b missing: build first (cmake --build $build)" >&2; exit 1; }
done
[[ -x /usr/bin/time ]] || { echo "bench: /usr/bin/time missing (apt-get install time)" >&2; exit 1; }
mkdir -p "$dir"

make_file() {  # size_mb op_mb [seed] -> path (bench/gen_cl, NX-style)
  local f="$dir/mixed-$1mb-op$2${3:+-seed$3}.cls"
  [[ -s $f ]] || "$gen" --size-mb "$1" --op-mb "$2" --seed "${3:-1}" >"$f"
  echo "$f"
}

make_apt_file() {  # size_mb op_mb -> path (bench/gen_apt, Creo-style)
  local f="$dir/creo-$1mb-op$2.ncl"
  [[ -s $f ]] || "$gen_apt" --size-mb "$1" --op-mb "$2" --seed 1 >"$f"
  echo "$f"
}

# One timed run: prints "seconds peak_kb".
timed() {
  /usr/bin/time -f "%e %M" -o "$dir/time.txt" "$@" >/dev/null 2>"$dir/stderr.txt" || {
    echo "bench: failed: $*" >&2; cat "$dir/stderr.txt" >&2; exit 1; }
  cat "$dir/time.txt"
}

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

mb() { awk -v b="$(stat -c %s "$1")" 'BEGIN {printf "%.1f", b/1e6}'; }

ratio() {  # [file] [label]
  local f=${1:-$(make_file 200 8)} label=${2:-"mixed (bench/gen_cl, NX-style)"}
  local size; size=$(mb "$f")
  : >"$dir/floor.t"; : >"$dir/clpc.t"; : >"$dir/clpc.rss"; : >"$dir/cert.t"; : >"$dir/cert.rss"
  for ((i = 0; i < runs; i++)); do
    timed "$floor" "$f" "$dir/floor.out" | awk '{print $1}' >>"$dir/floor.t"
    timed "$clpc" compile "$f" -t "$machine" -o "$dir/out.nc" --no-verify >"$dir/one.txt"
    awk '{print $1}' "$dir/one.txt" >>"$dir/clpc.t"
    awk '{print $2}' "$dir/one.txt" >>"$dir/clpc.rss"
    timed "$clpc" compile "$f" -t "$machine" -o "$dir/out.nc" >"$dir/one.txt"
    awk '{print $1}' "$dir/one.txt" >>"$dir/cert.t"
    awk '{print $2}' "$dir/one.txt" >>"$dir/cert.rss"
  done
  local tf tc rss tv rv
  tf=$(median <"$dir/floor.t"); tc=$(median <"$dir/clpc.t"); rss=$(sort -n "$dir/clpc.rss" | tail -1)
  tv=$(median <"$dir/cert.t"); rv=$(sort -n "$dir/cert.rss" | tail -1)
  awk -v s="$size" -v tf="$tf" -v tc="$tc" -v r="$rss" -v tv="$tv" -v rv="$rv" -v n="$runs" -v m="$machine" -v l="$label" 'BEGIN {
    printf "ratio: %s MB %s, %d alternating runs, medians\n", s, l, n
    printf "  floor                      %6.2f s  %7.1f MB/s\n", tf, s/tf
    printf "  clpc --no-verify (%s) %6.2f s  %7.1f MB/s  peak RSS %.1f MB\n", m, tc, s/tc, r/1024
    printf "  clpc, certified            %6.2f s  %7.1f MB/s  peak RSS %.1f MB\n", tv, s/tv, rv/1024
    printf "  clpc --no-verify / floor   %6.2f (target: at most 2)\n", tc/tf
    printf "  certified / floor          %6.2f (target: at most 2.5)\n", tv/tf
    printf "  certified / --no-verify    %6.2f (target: at most 1.25)\n", tv/tc }'
}

ratios() {
  ratio "$(make_file 200 8)" "mixed (bench/gen_cl, NX-style)"
  ratio "$(make_apt_file 200 8)" "mixed (bench/gen_apt, Creo-style)"
}

# Eight 25 MB files (eight seeds) in one command, certified: -j 1 against -j 2, alternating.
jobs() {
  local files=() i
  for i in 1 2 3 4 5 6 7 8; do files+=("$(make_file 25 8 "$i")"); done
  mkdir -p "$dir/jobs"
  : >"$dir/j1.t"; : >"$dir/j2.t"
  for ((i = 0; i < runs; i++)); do
    timed "$clpc" compile "${files[@]}" -t "$machine" --output-dir "$dir/jobs" -j 1 | awk '{print $1}' >>"$dir/j1.t"
    timed "$clpc" compile "${files[@]}" -t "$machine" --output-dir "$dir/jobs" -j 2 | awk '{print $1}' >>"$dir/j2.t"
  done
  awk -v a="$(median <"$dir/j1.t")" -v b="$(median <"$dir/j2.t")" -v n="$runs" 'BEGIN {
    printf "jobs: eight 25 MB files, certified, %d alternating runs, medians\n", n
    printf "  -j 1  %6.2f s\n  -j 2  %6.2f s\n  speed-up %.2f (target: at least 1.6)\n", a, b, a/b }'
}

rss() {
  local f; f=$(make_file 1000 20)
  local out; out=$(timed "$clpc" compile "$f" -t "$machine" -o "$dir/out.nc")
  awk -v s="$(mb "$f")" -v t="${out% *}" -v r="${out#* }" 'BEGIN {
    printf "rss: %s MB mixed, operations of at most 20 MB\n", s
    printf "  clpc %.2f s  %.1f MB/s  peak RSS %.1f MB (target: under 128 MB)\n", t, s/t, r/1024 }'
}

linear() {
  echo "linear: clpc time per MB (median of 3)"
  for size in 10 100 1000; do
    local f; f=$(make_file "$size" 8)
    : >"$dir/lin.t"
    for ((i = 0; i < 3; i++)); do timed "$clpc" compile "$f" -t "$machine" -o "$dir/out.nc" | awk '{print $1}' >>"$dir/lin.t"; done
    awk -v s="$(mb "$f")" -v t="$(median <"$dir/lin.t")" 'BEGIN { printf "  %7.1f MB  %7.2f s  %6.1f MB/s  %.2f ms/MB\n", s, t, s/t, 1000*t/s }'
  done
}

case ${1:-all} in
  ratio) ratios ;;
  rss) rss ;;
  linear) linear ;;
  jobs) jobs ;;
  all) ratios; rss; linear; jobs ;;
  *) echo "usage: bench/run.sh [ratio|rss|linear|jobs|all]" >&2; exit 2 ;;
esac
