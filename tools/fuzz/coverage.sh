#!/usr/bin/env bash
# coverage.sh [SECONDS]: line coverage of src/core reached by fuzzing.
#
# 1. the generated seed corpus (fuzz_board_replay --write-seeds),
# 2. SECONDS (default 60) of libFuzzer on it (build-fuzz: ASan + UBSan),
# 3. every input of the resulting corpus run once by a build instrumented
#    for source coverage (build-fuzzcov: clang -fprofile-instr-generate
#    -fcoverage-mapping), then llvm-profdata + llvm-cov report on src/core.
#
# Needs clang, libclang-rt (libFuzzer) and llvm (llvm-profdata, llvm-cov) of
# the same version. Prints the per-file table and the TOTAL line; the corpus
# is kept in build-fuzz/corpus. Run from the repository root.
set -euo pipefail
seconds=${1:-60}
corpus=build-fuzz/corpus

CC=clang cmake -S . -B build-fuzz -DXGO_FUZZ=ON -DXGO_BUILD_HOST=OFF -DXGO_BUILD_TESTS=OFF >/dev/null
cmake --build build-fuzz -j2 --target fuzz_board fuzz_board_replay >/dev/null
CC=clang cmake -S . -B build-fuzzcov -DXGO_FUZZ=ON -DXGO_BUILD_HOST=OFF -DXGO_BUILD_TESTS=OFF \
  -DCMAKE_C_FLAGS="-fprofile-instr-generate -fcoverage-mapping" >/dev/null
cmake --build build-fuzzcov -j2 --target fuzz_board >/dev/null

rm -rf "$corpus" && mkdir -p "$corpus"
./build-fuzz/fuzz_board_replay --write-seeds "$corpus"
if ! ./build-fuzz/fuzz_board -max_total_time="$seconds" -print_final_stats=1 \
     -artifact_prefix=build-fuzz/ "$corpus" > build-fuzz/fuzz.log 2>&1; then
  grep -E 'broken promise|ERROR|SUMMARY|Test unit written' build-fuzz/fuzz.log
  echo "the fuzzer found a broken promise (replay: ./build/fuzz_board_replay build-fuzz/crash-...)"
  exit 1
fi
grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added)' build-fuzz/fuzz.log

rm -f build-fuzzcov/fuzz.profraw
LLVM_PROFILE_FILE=build-fuzzcov/fuzz.profraw ./build-fuzzcov/fuzz_board -runs=0 "$corpus" \
  >/dev/null 2>&1
llvm-profdata merge -sparse build-fuzzcov/fuzz.profraw -o build-fuzzcov/fuzz.profdata
echo "corpus: $(ls "$corpus" | wc -l) inputs after ${seconds} s"
llvm-cov report ./build-fuzzcov/fuzz_board -instr-profile=build-fuzzcov/fuzz.profdata src/core |
  awk 'NR > 2 && NF > 10 { printf "%-18s lines %5s missed %4s  %s\n", $1, $8, $9, $10 }'
