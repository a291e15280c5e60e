#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (AddressSanitizer + UBSan) and runs each for a given
# time, from seed corpora (fuzz_certify, the differential target, from random choices; the
# others from the repository's CL files: tests/golden, tests/offsets, examples),
# ../shared/corpus when it is there, and fuzz/seeds; machine descriptions from machines.toml,
# tests/machines and examples, one machine per seed.
#
#   bash fuzz/run.sh [SECONDS_PER_TARGET]     default 600 (ten minutes each, forty minutes in all)
#
# Prints each target's executions and findings; exits 1 if anything crashed, hung or leaked.
# A finding is left in build-fuzz/artifacts/: reproduce it with build-fuzz/fuzz/TARGET FILE,
# fix it, and keep the input in tests/fuzz_regressions/ (tests/test_fuzz_regressions.cpp runs
# every file there through the compiler and the machine loader).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
build=build-fuzz
bash scripts/setup.sh >/dev/null
CC=clang CXX=clang++ cmake -S . -B $build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCLPC_FUZZ=ON \
  -DCLPC_TESTS=OFF -DCLPC_BENCH=OFF >/dev/null
cmake --build $build --target fuzz_parse fuzz_compile fuzz_machine fuzz_certify >/dev/null

corpus=$build/corpus
mkdir -p "$corpus"/{parse,compile,machine} $build/artifacts
seed_cl() {
  local dir=$1
  cp tests/golden/*.cls tests/golden/*.ncl tests/offsets/*.cls examples/*.cls tests/machines/*.cls "$dir"/ 2>/dev/null || true
  cp fuzz/seeds/parse/* "$dir"/ 2>/dev/null || true
  if [[ -d ../shared/corpus ]]; then
    for f in ../shared/corpus/*/*; do
      case $f in *LICENSE|*MANIFEST*) continue ;; esac
      # Small pieces: libFuzzer mutates short inputs best.
      head -c 4096 "$f" >"$dir/$(basename "$f").head"
    done
  fi
}
seed_cl "$corpus/parse"
seed_cl "$corpus/compile"
# Seeds of the repeating form (a first byte 0xFF: the rest over and over, past a read window).
for f in tests/golden/creo_mill.ncl examples/bracket.cls; do
  for t in parse compile; do { printf '\xff'; cat "$f"; } >"$corpus/$t/repeat-$(basename "$f")"; done
done
# One machine per seed file.
python3 - "$corpus/machine" machines.toml tests/machines/*.toml examples/*.toml tests/offsets/machines.toml <<'PY'
import re, sys, os
out = sys.argv[1]
n = 0
for path in sys.argv[2:]:
    text = open(path).read()
    parts = re.split(r'(?m)^(?=\[[^\[.\]]+\]\s*$)', text)
    for p in parts:
        if p.strip():
            open(os.path.join(out, f"seed{n}.toml"), "w").write(p)
            n += 1
PY
cp fuzz/seeds/machine/* "$corpus/machine"/ 2>/dev/null || true
# fuzz_certify's inputs are choices, not text: random bytes for each family (the first byte).
mkdir -p "$corpus/certify"
for i in 0 1 2 3 4 5 6 7; do head -c 600 /dev/urandom >"$corpus/certify/random$i"; done

status=0
report=""
for t in parse compile machine certify; do
  log=$build/fuzz_$t.log
  max_len=16384
  [[ $t == machine ]] && max_len=8192
  set +e
  $build/fuzz/fuzz_$t "$corpus/$t" -max_total_time="$seconds" -print_final_stats=1 -max_len=$max_len -timeout=20 \
    -rss_limit_mb=2048 -artifact_prefix="$build/artifacts/$t-" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | awk '{print $2}' | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | awk '{print $2}')
  if [[ $rc -ne 0 ]]; then
    status=1
    report+="  fuzz_$t: FOUND A PROBLEM (exit $rc) after ${execs:-?} executions: see $log and $build/artifacts/"$'\n'
  else
    report+="  fuzz_$t: ${execs:-?} executions in ${seconds} s, coverage ${cov:-?} edges, no findings"$'\n'
  fi
done
echo "fuzz: $((4 * seconds)) s in all"
printf '%s' "$report"
exit $status
