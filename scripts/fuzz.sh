#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, -DQUADTRI_FUZZ=ON, ASan + UBSan) in build-fuzz/ and
# runs each for SECONDS (default 60), seeded with tests/fuzz-regressions/NAME/, the project's
# scenes and meshes, and Debian's assimp-testmodels where installed. New corpus entries go to
# build-fuzz/corpus/NAME/ (not tracked); a crash, leak or timeout stops the run, leaves its input
# as build-fuzz/artifacts/NAME/crash-* (leak-*, timeout-*) and makes the script fail. Copy such
# an input into tests/fuzz-regressions/NAME/ once the bug is fixed: ctest replays it.
#
#   scripts/fuzz.sh [SECONDS] [NAME...]      NAME: obj ply off stl scene_xml shape_spec cli_text
#                                            render_state (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  names=(obj ply off stl scene_xml shape_spec cli_text render_state)
fi
build=${FUZZ_BUILD:-build-fuzz}
jobs=${JOBS:-$(nproc)}
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DQUADTRI_FUZZ=ON -DQUADTRI_BENCH=OFF -DQUADTRI_PYTHON=OFF -DBUILD_TESTING=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${names[@]/#/fuzz_}"

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
status=0
for name in "${names[@]}"; do
  corpus="$build/corpus/$name" artifacts="$build/artifacts/$name"
  mkdir -p "$corpus" "$artifacts"
  extra=()
  for d in $(seeds "$name"); do [ -d "$d" ] && extra+=("$d"); done
  echo "== fuzz_$name for ${seconds}s"
  # -rss_limit_mb: a harness may use what --max-memory allows it (256 MiB) and ASan's overhead.
  if ! "$build/fuzz/fuzz_$name" "$corpus" "tests/fuzz-regressions/$name" "${extra[@]}" \
      -max_total_time="$seconds" -timeout=20 -rss_limit_mb=3072 -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="$artifacts/" 2>"$build/fuzz-$name.log"; then
    echo "fuzz_$name FAILED: see $build/fuzz-$name.log and $artifacts/" >&2
    status=1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$build/fuzz-$name.log" || true
done
exit $status
