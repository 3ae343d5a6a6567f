#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Coverage-guided fuzzing with libFuzzer under ASan + UBSan (clang-16, build-fuzz/).
#
#   scripts/fuzz.sh [TARGET...] [--minutes N | --seconds N] [--jobs N] [--keep | --no-keep] [--build-dir DIR]
#
# Configures build-fuzz/ once (clang++-16, -DHIL_FUZZ=ON), builds the fuzz targets while holding
# one of the machine-wide build slots (like /work/bin/hil-build), then runs each TARGET (default:
# every target, names as in build-fuzz/fuzz_targets.txt without the fuzz_ prefix) for the given
# time (default 10 minutes each) starting from its corpus in the repository. With --keep (the
# default for campaigns of a minute or more) the inputs that reach new coverage are merged into
# the repository corpus (`-merge=1`: only what adds coverage), so the next run and the CI replay
# start from there. A crash, leak, timeout or sanitizer report is saved to
# build-fuzz/findings/TARGET/ and fails the script. Per target it prints executions, coverage
# (edges, features) and findings, also written to build-fuzz/fuzz-report.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)

seconds=600
jobs=1
keep=""
bd="$src/build-fuzz"
targets=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --minutes) seconds=$(( $2 * 60 )); shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    --no-keep) keep=0; shift ;;
    --build-dir) bd=$2; shift 2 ;;
    -h|--help) sed -n '3,16p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[[ -z "$keep" ]] && { (( seconds >= 60 )) && keep=1 || keep=0; }

for tool in clang++-16 clang-16 ninja; do
  command -v "$tool" >/dev/null || { echo "fuzz.sh: $tool missing: bash scripts/install-deps.sh" >&2; exit 2; }
done

if [[ ! -f "$bd/CMakeCache.txt" ]]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  CC=clang-16 CXX=clang++-16 cmake -S "$src" -B "$bd" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHIL_FUZZ=ON \
    -DHIL_BUILD_TESTS=ON -DHIL_BUILD_BENCH=OFF -DHIL_WERROR=OFF "${launcher[@]}" >/dev/null
fi
# The list of targets comes from the configure step (hil_add_fuzzer records NAME=CORPUS).
cmake "$bd" >/dev/null
mapfile -t lines < <(grep '=' "$bd/fuzz_targets.txt")
declare -A corpus_of=()
for l in "${lines[@]}"; do corpus_of["${l%%=*}"]="${l#*=}"; done
if [[ ${#targets[@]} -eq 0 ]]; then
  for l in "${lines[@]}"; do targets+=("${l%%=*}"); done
fi
build_targets=()
for t in "${targets[@]}"; do
  [[ -n "${corpus_of[$t]:-}" ]] || { echo "fuzz.sh: no fuzz target '$t' (see $bd/fuzz_targets.txt)" >&2; exit 2; }
  build_targets+=("fuzz_$t")
done

# Build while holding a build slot, as /work/bin/hil-build does (slots 1..3).
build() {
  if [[ -d /work/bin && -x /work/bin/hil-build ]]; then
    while :; do
      for s in 1 2 3; do
        exec 9>/tmp/hil-build-slot$s
        if flock -n 9; then
          nice -n 5 cmake --build "$bd" -j2 --target "${build_targets[@]}"
          local rc=$?
          exec 9>&-
          return $rc
        fi
      done
      sleep 3
    done
  fi
  cmake --build "$bd" -j"$(nproc)" --target "${build_targets[@]}"
}
build

report="$bd/fuzz-report.txt"
: >"$report"
status=0
printf '%-26s %12s %8s %8s %8s  %s\n' target executions edges features corpus findings | tee -a "$report"
for t in "${targets[@]}"; do
  corpus="${corpus_of[$t]}"
  mkdir -p "$corpus"
  fresh=$(mktemp -d)
  stamp="$fresh.started"  # findings of earlier runs stay in $findings; count only this run's
  : >"$stamp"
  findings="$bd/findings/$t"
  mkdir -p "$findings"
  log="$bd/logs/$t.log"
  mkdir -p "$(dirname "$log")"
  dict=()
  [[ -f "$(dirname "$corpus")/$t.dict" ]] && dict=(-dict="$(dirname "$corpus")/$t.dict")
  bin=$(find "$bd" -name "fuzz_$t" -type f -perm -u+x | head -1)
  par=()
  (( jobs > 1 )) && par=(-jobs="$jobs" -workers="$jobs")
  rc=0
  # New inputs go to $fresh; the repository corpus is read as seeds only. Parallel jobs write
  # their logs (fuzz-N.log) to the working folder: $bd.
  (cd "$bd" && "$bin" "$fresh" "$corpus" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$findings/" "${par[@]}") >"$log" 2>&1 || rc=$?
  # Parallel jobs leave fuzz-N.log beside the main log; without them the glob matches nothing.
  job_logs=("$log")
  for f in "$bd"/fuzz-*.log; do if [[ -e "$f" ]]; then job_logs+=("$f"); fi; done
  execs=$(cat "${job_logs[@]}" | awk '/stat::number_of_executed_units/ {s+=$2} END {print s+0}')
  last=$(grep -E '^#[0-9]+.*(cov|DONE)' "$log" | tail -1 || true)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<<"$last")
  if [[ "$keep" == 1 ]]; then
    (cd "$bd" && "$bin" -merge=1 "$corpus" "$fresh") >>"$log" 2>&1 || true
  fi
  rm -rf "$fresh" "$bd"/fuzz-*.log
  n_corpus=$(find "$corpus" -type f | wc -l)
  found=$(find "$findings" -type f -newer "$stamp" | wc -l)
  rm -f "$stamp"
  what="none"
  if [[ $rc -ne 0 || $found -ne 0 ]]; then
    status=1
    what="$found in $findings (exit $rc; log $log)"
    grep -m3 -E 'ERROR: |runtime error|SUMMARY' "$log" | sed 's/^/    /' || true
  fi
  printf '%-26s %12s %8s %8s %8s  %s\n' "$t" "$execs" "${cov:-?}" "${ft:-?}" "$n_corpus" "$what" | tee -a "$report"
done
exit $status
