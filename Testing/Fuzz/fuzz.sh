#!/usr/bin/env bash
# Builds the libFuzzer target with clang (ASan + UBSan) and fuzzes Core for a bounded time.
#   Testing/Fuzz/fuzz.sh [seconds=60] [build folder=build/fuzz]
# New inputs go to a scratch corpus in the build folder; the seed corpus in the repository is read
# only. A crash leaves its input as crash-* in the build folder: add it to corpus/ and fix it.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$here/../.."
seconds="${1:-60}"
out="${2:-$root/build/fuzz}"
mkdir -p "$out/corpus"
clang++ -std=c++17 -O1 -g -ffp-contract=off -fsanitize=fuzzer,address,undefined \
  -fno-sanitize-recover=undefined -I"$root/Core/include" -I"$root/Core/src" -I"$here/../Validation" \
  "$here/FuzzTriangulate.cxx" "$root"/Core/src/*.cxx "$root"/Core/src/*/*.cxx "$here/../Validation/ExactValidator.cxx" \
  -lgmpxx -lgmp -o "$out/FuzzTriangulate"
cd "$out"
./FuzzTriangulate -max_total_time="$seconds" -max_len=2048 -timeout=20 -print_final_stats=1 \
  corpus "$here/corpus" 2>&1 | tail -n 12
