#!/usr/bin/env bash
# Runs the libFuzzer harnesses for SECONDS each (default 60), JOBS at a time (default: the
# cores), seeded with tests/fuzz-regressions/NAME/, the project's scenes and meshes, and
# Debian's assimp-testmodels where installed. The harnesses are built in FUZZ_BUILD (default
# build-asan, the sanitizer build of `make sanitize`: clang, -DQUADTRI_FUZZ=ON, ASan + UBSan),
# which is configured here only when it is not a fuzz build yet. New corpus entries go to
# FUZZ_BUILD/corpus/NAME/ (not tracked); a crash, leak or timeout stops that harness, leaves its
# input as FUZZ_BUILD/artifacts/NAME/crash-* (leak-*, timeout-*, oom-*), prints it (compressed,
# base64) so that a finding on a machine that is gone can be replayed, and makes the script fail.
# Copy such an input into tests/fuzz-regressions/NAME/ once the bug is fixed: ctest replays it.
#
#   scripts/fuzz.sh [SECONDS] [NAME...]      NAME: obj ply off stl scene_xml shape_spec cli_text
#                                            render_state (default: all)
#   FUZZ_SEED=1 scripts/fuzz.sh 60           CI's reproducible run (see ci_runs below)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  names=(obj ply off stl scene_xml shape_spec cli_text render_state)
fi
build=${FUZZ_BUILD:-build-asan}
jobs=${JOBS:-$(nproc)}
if ! grep -qs '^QUADTRI_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
    -DQUADTRI_FUZZ=ON -DQUADTRI_BENCH=OFF -DCMAKE_UNITY_BUILD="${UNITY:-ON}" >/dev/null
fi
cmake --build "$build" -j "$jobs" --target "${names[@]/#/fuzz_}"

# FUZZ_SEED=N: a reproducible run, as CI's. libFuzzer starts from seed N and stops after a fixed
# number of inputs per harness (below: each takes 15 to 45 s here, two at a time on 2 cores),
# SECONDS remaining only a cap. The same binary then explores the same inputs on any
# machine, so a finding in CI is one this script finds here, and a run cut short by the cap
# explores a prefix of them. Another binary explores other inputs: the unity build (the
# Makefile's default) took shape_spec's 25,000 inputs towards larger shapes, 54 s alone against
# 6 s for the file-by-file build, so the counts are for the unity build.
ci_runs() {
  case "$1" in
    stl) echo 10000 ;;
    shape_spec) echo 12000 ;;
    obj) echo 12000 ;;
    ply) echo 40000 ;;
    off) echo 60000 ;;
    render_state) echo 150000 ;;
    scene_xml) echo 300000 ;;
    cli_text) echo 500000 ;;
  esac
}

assimp=/usr/share/assimp/models
seeds() {  # extra seed folders for a harness
  case "$1" in
    obj) echo scenes/meshes "$assimp/OBJ" ;;
    ply) echo "$assimp/PLY" ;;
    off) echo "$assimp/OFF" ;;
    stl) echo "$assimp/STL" ;;
    scene_xml) echo scenes/mitsuba scenes/thesis ;;
  esac
}
# Assimp's own leaks on malformed files (fuzz/lsan.supp says which and why).
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
run() {  # one harness; its log holds libFuzzer's final statistics
  local name=$1 corpus="$build/corpus/$1" artifacts="$build/artifacts/$1" extra=()
  mkdir -p "$corpus" "$artifacts"
  for d in $(seeds "$name"); do [ -d "$d" ] && extra+=("$d"); done
  if [ -n "${FUZZ_SEED:-}" ]; then
    extra+=("-seed=$FUZZ_SEED" "-runs=$(ci_runs "$name")")
    rm -rf "$corpus" && mkdir -p "$corpus"  # the same start on every machine
  fi
  # -rss_limit_mb: a harness may use what --max-memory allows it (256 MiB) and ASan's overhead.
  "$build/fuzz/fuzz_$name" "$corpus" "tests/fuzz-regressions/$name" "${extra[@]}" \
    -max_total_time="$seconds" -timeout=20 -rss_limit_mb=3072 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" >"$build/fuzz-$name.log" 2>&1
}
echo "== ${#names[@]} harnesses for ${seconds}s each${FUZZ_SEED:+ at most (seed $FUZZ_SEED, a fixed input count each)}, $jobs at a time"
declare -A pids
status=0
report() {  # waits for one harness and prints its result
  local name=$1
  if wait "${pids[$name]}"; then
    echo "fuzz_$name: $(grep -E '^stat::number_of_executed_units' "$build/fuzz-$name.log" |
      awk '{print $2}') executions, peak $(grep -E '^stat::peak_rss_mb' "$build/fuzz-$name.log" |
      awk '{print $2}') MiB, nothing found"
  else
    echo "fuzz_$name FAILED: see $build/fuzz-$name.log and $build/artifacts/$name/" >&2
    grep -E "^==[0-9]+==ERROR|SUMMARY|^artifact_prefix|Test unit written" \
      "$build/fuzz-$name.log" >&2 || true
    # The input itself, so that a finding on a CI machine (whose files are gone) can be replayed:
    # up to 12 KiB compressed, as base64.
    local input
    for input in "$build/artifacts/$name"/*; do
      [ -f "$input" ] || continue
      local packed
      packed=$(gzip -9c "$input" | base64 -w0)
      if [ ${#packed} -le 16384 ]; then
        echo "input $(basename "$input") ($(stat -c %s "$input") bytes); to replay it:" >&2
        echo "  echo $packed | base64 -d | gunzip > input && $build/fuzz/fuzz_$name input" >&2
      fi
    done
    status=1
  fi
}
running=()
for name in "${names[@]}"; do
  run "$name" &
  pids[$name]=$!
  running+=("$name")
  if [ ${#running[@]} -ge "$jobs" ]; then
    report "${running[0]}"
    running=("${running[@]:1}")
  fi
done
for name in "${running[@]}"; do report "$name"; done
exit $status
