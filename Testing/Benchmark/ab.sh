#!/usr/bin/env bash
# A/B of the kernel against an earlier commit's, on this machine, in interleaved runs.
#   Testing/Benchmark/ab.sh <commit> [kinds=cube,ball,torus,ellipsoid] [points=1000000]
#                           [runs=5] [threads=1] [voronoi | periodic | periodic-voronoi | weighted]
# Builds <commit>'s Core and the working tree's in build-ab/ (Release, as setup.sh builds), both
# timed by the same driver (ab/ABDriver.cxx) on the same generated points, then runs them in
# turn, A then B on even runs and B then A on odd ones, and prints for each point set the best
# and worst of the runs, the ratio of the bests (A over B: above 1 means the working tree is
# faster) and whether the outputs' hashes agree.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
commit="${1:?usage: $0 <commit> [kinds] [points] [runs] [threads] [mode]}"
kinds="${2:-cube,ball,torus,ellipsoid}"
points="${3:-1000000}"
runs="${4:-5}"
threads="${5:-1}"
mode="${6:-}"
out="$root/build-ab"
sha="$(git -C "$root" rev-parse --short "$commit")"

build() { # <name> <Core folder>
  cmake -S "$here/ab" -B "$out/$1" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFD3_AB_CORE="$2" \
    >/dev/null
  cmake --build "$out/$1" -j2 >/dev/null
}
rm -rf "$out/src-$sha"
mkdir -p "$out/src-$sha"
git -C "$root" archive "$sha" Core | tar -x -C "$out/src-$sha"
build "A-$sha" "$out/src-$sha/Core"
build B-worktree "$root/Core"
a="$out/A-$sha/ABDriver"
b="$out/B-worktree/ABDriver"

echo "A: $sha   B: working tree   $points points, $threads thread(s), $runs interleaved runs ${mode}"
echo "| set | A best | A worst | B best | B worst | A/B | hashes |"
echo "|---|---:|---:|---:|---:|---:|---|"
for kind in ${kinds//,/ }; do
  ta=() tb=() ha="" hb=""
  for ((r = 0; r < runs; ++r)); do
    if ((r % 2 == 0)); then
      read -r sa ha _ < <("$a" "$kind" "$points" "$threads" $mode)
      read -r sb hb _ < <("$b" "$kind" "$points" "$threads" $mode)
    else
      read -r sb hb _ < <("$b" "$kind" "$points" "$threads" $mode)
      read -r sa ha _ < <("$a" "$kind" "$points" "$threads" $mode)
    fi
    ta+=("$sa") tb+=("$sb")
  done
  printf '%s\n' "${ta[@]}" >"$out/a.txt"
  printf '%s\n' "${tb[@]}" >"$out/b.txt"
  amin=$(sort -g "$out/a.txt" | head -1) amax=$(sort -g "$out/a.txt" | tail -1)
  bmin=$(sort -g "$out/b.txt" | head -1) bmax=$(sort -g "$out/b.txt" | tail -1)
  same=$([ "$ha" = "$hb" ] && echo "same $ha" || echo "DIFFER $ha $hb")
  echo "| $kind | $amin | $amax | $bmin | $bmax | $(awk -v a="$amin" -v b="$bmin" 'BEGIN { printf "%.3f", a / b }') | $same |"
done
