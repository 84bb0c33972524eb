#!/usr/bin/env bash
# The scaling runs for a lent many-core machine that has no ParaView: builds ScalingModel (Core,
# the point sets and the scaling model, no VTK, no Voro++) statically into build-device/, from
# build/'s Core (./setup.sh first), and prints the command that runs it there.
#   Testing/Benchmark/static_scaling.sh [kinds=cube,ball,clusters,ellipsoid] [points=4000000]
#                                       [threads=1,2,4,8,16]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
kinds="${1:-cube,ball,clusters,ellipsoid}"
points="${2:-4000000}"
threads="${3:-1,2,4,8,16}"
cmake --build "$root/build" --target FastDelaunayCore -j2 >/dev/null
mkdir -p "$root/build-device"
# -mfma as Core's build uses it where the building machine has FMA (the lent machines do).
g++ -O3 -DNDEBUG -std=c++17 -static -mfma -DFD3_BENCHMARK_SOURCE_DIR=\"unused\" \
  -I"$root/Core/include" -I"$root/Testing/Validation" -I"$root/Testing/Benchmark" \
  "$root/Testing/Benchmark/ScalingModel.cxx" "$root/Testing/Benchmark/Scaling.cxx" \
  "$root/Testing/Benchmark/VoronoiBench.cxx" "$root/Testing/Validation/PointSets.cxx" \
  "$root/build/lib/libFastDelaunayCore.a" -lgmp \
  -Wl,--whole-archive -lpthread -Wl,--no-whole-archive -o "$root/build-device/ScalingModel" \
  2> >(grep -v "getaddrinfo" >&2)
echo "run there (carry build-device):"
echo "  build-device/ScalingModel --scaling --kinds $kinds --sizes $points --threads $threads" \
  "--markdown \$OUT/scaling.md --csv \$OUT/scaling.csv"
