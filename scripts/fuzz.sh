#!/usr/bin/env bash
# Builds the libFuzzer targets in fuzz/ with clang (ASan + UBSan) in build-fuzz/ and runs each
# for SECONDS (default 600), two at a time. The seed corpus fuzz/corpus/<target>/ and past
# findings fuzz/regressions/<target>/ are copied to a scratch corpus build-fuzz/corpus/<target>/
# (the repo's corpus stays small); crash, timeout and OOM inputs go to build-fuzz/findings/<target>/.
# Prints one summary line per target; exits 1 if any target found something.
#   scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 60 units manifest
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECS="${1:-600}"
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(csv_table run_csv manifest units session cli_args)
B="$ROOT/build-fuzz"
JOBS="${FUZZ_JOBS:-2}"

if ! command -v clang++ >/dev/null; then
  echo "fuzz.sh: installing clang (libFuzzer ships with Debian's clang)"
  apt-get install -y clang || { echo "fuzz.sh: clang++ not found and could not be installed" >&2; exit 2; }
fi

mkdir -p "$B"
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$ROOT")}"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S "$ROOT" -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DSTICKSLIP_FUZZ=ON \
  -DSTICKSLIP_BUILD_PYTHON=OFF -DSTICKSLIP_BUILD_BENCH=OFF -DBUILD_TESTING=OFF -DSTICKSLIP_WITH_MPI=OFF \
  "${launcher[@]}" >"$B/configure.log" 2>&1 || { cat "$B/configure.log"; exit 2; }
cmake --build "$B" -j"$JOBS" --target "${TARGETS[@]/#/fuzz_}" || exit 2

mkdir -p "$B/logs"
# Reviewed leaks in Qt itself (see the file); everything else LeakSanitizer reports is a finding.
export LSAN_OPTIONS="suppressions=$ROOT/fuzz/lsan.supp:print_suppressions=0"
run_one() {
  local t="$1" corpus="$B/corpus/$1" found="$B/findings/$1" dict=()
  rm -rf "$found"; mkdir -p "$corpus" "$found"
  cp -n "$ROOT/fuzz/corpus/fuzz_$t/"* "$corpus/" 2>/dev/null
  cp -n "$ROOT/fuzz/regressions/fuzz_$t/"* "$corpus/" 2>/dev/null
  [ -f "$ROOT/fuzz/fuzz_$t.dict" ] && dict=(-dict="$ROOT/fuzz/fuzz_$t.dict")
  # -timeout: one input running 10 s is a hang; -rss_limit_mb: a 2 GB input is a finding.
  QT_QPA_PLATFORM=offscreen "$B/fuzz/fuzz_$t" "$corpus" "${dict[@]}" -max_total_time="$SECS" -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$found/" -print_final_stats=1 >"$B/logs/$t.log" 2>&1
}

pids=()
for t in "${TARGETS[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
  echo "fuzz.sh: fuzz_$t for ${SECS}s (log: build-fuzz/logs/$t.log)"
  run_one "$t" &
done
wait

status=0
printf '%-10s %12s %8s %8s %10s %9s\n' target executions exec/s cov corpus findings
for t in "${TARGETS[@]}"; do
  log="$B/logs/$t.log"
  execs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | awk '{print $2}' | tail -1)
  rate=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$log" | awk '{print $2}' | tail -1)
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | awk '{print $2}')
  corp=$(ls "$B/corpus/$t" | wc -l)
  found=$(ls "$B/findings/$t" | wc -l)
  [ "$found" -gt 0 ] && status=1
  printf '%-10s %12s %8s %8s %10s %9s\n' "$t" "${execs:-?}" "${rate:-?}" "${cov:-?}" "$corp" "$found"
  for f in "$B/findings/$t/"*; do [ -e "$f" ] && echo "  finding: ${f#$ROOT/}"; done
done
exit $status
