#!/usr/bin/env bash
# Fuzzes the mesh readers, the mesh check and a small deform/flatten of what
# parses (fuzz/fuzz_mesh.cpp) with libFuzzer under ASan+UBSan.
#   bash scripts/fuzz.sh                 # the short run of the test command (fixed executions)
#   bash scripts/fuzz.sh --seconds 3600  # a long run
# Needs the sanitizer tree built with -DANISO_FUZZ=ON (scripts/test.sh does it).
# Budgets per input: 2 s and 512 MB (-timeout, -rss_limit_mb, -malloc_limit_mb)
# for inputs up to 100 KB. A finding is written to $BUILD/fuzz/findings/ and
# the run fails: copy the file into fuzz/regressions/ (ctest replays it), fix,
# and run again.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${ANISO_FUZZ_BUILD_DIR:-build-asan}
shared=${ANISO_SHARED_DIR:-../shared}
# The test command's short run: two runs of 2,500 executions side by side,
# one per core (one run of 5,000 left a core idle for 9 s), each with a fixed
# mutation seed and a corpus of its own: the same code gives the same runs,
# so their verdict is the code's, not the draw's (a long run, or --runs,
# draws a new seed each time to explore).
halves=(1 2)
limit=(-runs=2500)
case "${1:-}" in
  --seconds) halves=(0); limit=(-max_total_time="$2") ;;
  --runs) halves=(0); limit=(-runs="$2") ;;
  "") ;;
  *) echo "usage: $0 [--seconds S | --runs N]" >&2; exit 2 ;;
esac

fuzzer="$build/fuzz/anisoform_fuzz_mesh"
[ -x "$fuzzer" ] || { echo "fuzz: $fuzzer is missing (build $build with -DANISO_FUZZ=ON)" >&2; exit 1; }

# Seeds: every real mesh up to 100 KB, behind the format byte the target reads
# (0 OBJ, 1 OFF, 2 PLY, 3 STL), plus the regression inputs.
seeds="$build/fuzz/seeds"
corpus="$build/fuzz/corpus"
findings="$build/fuzz/findings"
mkdir -p "$seeds" "$corpus" "$findings"
while IFS= read -r -d '' mesh; do
  case "${mesh,,}" in
    *.obj) byte='\x00' ;; *.off) byte='\x01' ;; *.ply) byte='\x02' ;; *.stl) byte='\x03' ;; *) continue ;;
  esac
  name=$(basename "$(dirname "$mesh")")_$(basename "$mesh")
  { printf "$byte"; cat "$mesh"; } > "$seeds/$name"
done < <(find "$shared/meshes" -type f -size -100k -print0)
cp fuzz/regressions/* "$seeds/" 2>/dev/null || true

# The fuzzer's own leak check covers what the run allocates; the seeds' order
# and the fixed seed make the short run reproducible. Half 0: one run, the
# whole output on the terminal, a seed drawn by libFuzzer. ASan holds freed
# memory back (its quarantine) to catch uses after free; at its default of
# 256 MB a long run's corpus of 1,600 inputs, read at the start, ran into the
# 512 MB RSS limit with a live heap of 42 MB. 64 MB still holds back the
# frees of many inputs (a small mesh's run frees a few MB).
run_fuzzer() {
  local half=$1 seed=() dir="$corpus"
  if [ "$half" != 0 ]; then seed=(-seed="$half"); dir="$corpus/$half"; mkdir -p "$dir"; fi
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0:quarantine_size_mb=64 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$fuzzer" "${limit[@]}" "${seed[@]}" -max_len=102401 -timeout=2 -rss_limit_mb=512 -malloc_limit_mb=512 \
      -print_final_stats=1 -artifact_prefix="$findings/" "$dir" "$seeds"
}
if [ "${halves[0]}" = 0 ]; then
  run_fuzzer 0
  exit
fi
pids=()
# An interrupted run (Ctrl-C, a failed CI step) ends both.
trap 'kill "${pids[@]}" 2>/dev/null || true' EXIT
for half in "${halves[@]}"; do
  run_fuzzer "$half" > "$build/fuzz/run-$half.log" 2>&1 &
  pids+=($!)
done
status=0
for i in "${!halves[@]}"; do
  half=${halves[$i]}
  if wait "${pids[$i]}"; then
    echo "fuzz: run $half (seed $half):"
    grep -E '^(Done|stat::)' "$build/fuzz/run-$half.log" | sed 's/^/  /'
  else
    status=1
    echo "fuzz: run $half (seed $half) failed; its output:" >&2
    cat "$build/fuzz/run-$half.log" >&2
  fi
done
exit "$status"
