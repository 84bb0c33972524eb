#!/usr/bin/env bash
# FastDelaunay3D set-up on Debian 12: installs the packages the build needs (skipping those already
# present), then configures and builds in Release with Ninja.
#
#   ./setup.sh          set up and build
#   ./setup.sh demo     ... then tetrahedralize Data/points.vtp under pvbatch into output/
#   ./setup.sh benchmark [sizes] [scaling size]   ... then benchmark Core, the filter,
#                       vtkDelaunay3D, CGAL and TetGen (sizes default 10000,100000,1000000) into
#                       output/benchmark.{md,csv,png}, the paper's Table 1 into output/table1.md,
#                       the Voronoi cells against Voro++ and scipy into output/voronoi.{md,csv},
#                       Fast Voronoi 3D under pvpython into output/pvpython-voronoi.md,
#                       weighted points against CGAL's regular triangulation and Voro++'s
#                       radical cells into output/weighted.{md,csv},
#                       instructions and cache misses per point for Core and CGAL (cachegrind)
#                       into output/work-per-point.md,
#                       and the threads' scaling model (1 to 64 threads, default 4000000 points)
#                       into output/scaling.{md,csv}
#   ./setup.sh test     ... then run the whole test suite (ctest under xvfb-run)
#   ./setup.sh vtk      ... then build against VTK alone, without ParaView: Debian's VTK 9.1
#                       (libvtk9-dev, python3-vtk9), which conflicts with ParaView's packages, is
#                       unpacked into build-vtk-sdk/, and the filters' tests, which need no
#                       ParaView, run in build-vtk (CI runs it after test)
#   ./setup.sh sanitizers  ... then the same suite built with AddressSanitizer +
#                       UndefinedBehaviorSanitizer (Debug: the kernel's own mesh check on; the
#                       portable fallbacks of the compiler intrinsics instead of the intrinsics) in
#                       build-asan, then the kernel's thread tests built with ThreadSanitizer in
#                       build-tsan (CI runs it after test)
set -euo pipefail
cd "$(dirname "$0")"

# ParaView's SDK (never libvtk9-dev: it conflicts with python3-paraview), the libraries its CMake
# package needs but does not pull in, an X server for rendering tests, and the test tools, with
# the tests' references Voro++ and CGAL (GPL-family licensed: linked into test and benchmark
# programs only, never into Core or Plugin).
packages=(paraview paraview-dev python3-paraview libopenmpi-dev libdouble-conversion-dev libglew-dev
  python3-dev xvfb xauth libgl1-mesa-dri openmpi-bin libgtest-dev libgmock-dev libgmp-dev
  cmake ninja-build g++ pkg-config clang clang-format libclang-rt-14-dev voro++-dev libcgal-dev)
# The benchmark also compares against TetGen and CGAL's parallel build (TBB), and plots.
[ "${1:-}" = benchmark ] &&
  packages+=(libtbb-dev libtet1.5-dev python3-matplotlib python3-scipy valgrind)
# Debian's VTK 9.1 finds TBB (its SMP backend) when a project finds it.
[ "${1:-}" = vtk ] && packages+=(libtbb-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# New commits are checked as CI checks them (.ci/check-commits), in a clone of the project.
if [ -d .git ] && [ -z "$(git config core.hooksPath || true)" ]; then
  git config core.hooksPath .githooks
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build -j2

plugin=build/lib/paraview-5.11/plugins/FastDelaunay3D/FastDelaunay3D.so
# -noreset: an X server resets when its last client leaves, and a test connecting during the
# reset fails ("bad X server connection"); the rendering tests run one after another, so each
# one's exit would otherwise reset it under the next.
xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
case "${1:-build}" in
  build) ;;
  demo) "${xvfb[@]}" pvbatch Testing/Python/demo.py "$plugin" Data/points.vtp output ;;
  benchmark)
    cmake -S . -B build >/dev/null # picks CGAL up if it was just installed
    cmake --build build --target Benchmark WorkPerPoint -j2
    mkdir -p output
    build/bin/Benchmark --sizes "${2:-10000,100000,1000000}" --markdown output/benchmark.md \
      --csv output/benchmark.csv --methods Core,vtkFastDelaunay3D,vtkDelaunay3D,CGAL,TetGen,Core-2,CGAL-2
    for ranks in 1 2 3 4; do # the distributed filter: time, rank 0's peak, ghost points
      mpiexec --allow-run-as-root --oversubscribe -np $ranks pvbatch --mpi \
        Testing/Benchmark/mpi_benchmark.py "$plugin" \
        "$(echo "${2:-1000000}" | tr ',' '\n' | tail -1)" 2>&1 | grep '^mpi_benchmark'
    done | tee output/mpi-benchmark.txt
    build/bin/Benchmark --table1 --markdown output/table1.md
    python3 Testing/Benchmark/work_per_point.py build/bin/WorkPerPoint 100000,1000000 cube \
      | tee output/work-per-point.md
    build/bin/Benchmark --voronoi --sizes "${2:-100000,1000000}" --threads 1,2 \
      --kinds cube,clusters,molshell,lattice --markdown output/voronoi.md --csv output/voronoi.csv
    PYTHONPATH="$PWD/build/lib/python3.11/site-packages" "${xvfb[@]}" pvpython \
      Testing/Benchmark/pvpython_voronoi.py "$plugin" "$(echo "${2:-1000000}" | tr ',' '\n' | tail -1)" \
      3 1 build/bin/Benchmark | tee output/pvpython-voronoi.md
    build/bin/Benchmark --weighted --sizes "${2:-100000,1000000}" --repeat 3 \
      --markdown output/weighted.md --csv output/weighted.csv
    build/bin/Benchmark --scaling --sizes "${3:-4000000}" --threads 1,2,4,8,16,32,64 \
      --kinds cube,ball,clusters,torus,cylinder,noisyshell,scans,terrain,molshell \
      --markdown output/scaling.md --csv output/scaling.csv
    /usr/bin/python3 Testing/Benchmark/plot.py output/benchmark.csv output/benchmark.png \
      "$(sed -n 's/^Machine: \([^.]*\)\..*/\1/p' output/benchmark.md)" ;;
  test) (cd build && "${xvfb[@]}" ctest -j2 --output-on-failure) ;;
  sanitizers)
    cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
      -DFD3_SANITIZE=ON -DFD3_PORTABLE=ON -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
    cmake --build build-asan -j2
    (cd build-asan && ASAN_OPTIONS=detect_leaks=1 "${xvfb[@]}" ctest -j2 --output-on-failure)
    cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFD3_SANITIZE_THREAD=ON \
      -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
    cmake --build build-tsan --target TestCore -j2
    TSAN_OPTIONS=halt_on_error=1 build-tsan/bin/TestCore \
      --gtest_filter='Threads.*:AddPoints.SameTetrahedra*:Voronoi.SameCells*' ;;
  vtk)
    sdk="$PWD/build-vtk-sdk"
    vtk_dir="$sdk/usr/lib/x86_64-linux-gnu/cmake/vtk-9.1"
    if [ ! -f "$vtk_dir/vtk-config.cmake" ]; then
      mkdir -p "$sdk/debs"
      (cd "$sdk/debs" && apt-get download libvtk9-dev libvtk9.1 python3-vtk9 vtk9 2>/dev/null)
      for deb in "$sdk"/debs/*.deb; do dpkg -x "$deb" "$sdk"; done
    fi
    cmake -S . -B build-vtk -G Ninja -DCMAKE_BUILD_TYPE=Release -DFD3_PARAVIEW=OFF \
      -DVTK_DIR="$vtk_dir" -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
    cmake --build build-vtk -j2
    # The kernel's own tests and the fuzzer do not touch VTK: test already ran them.
    (cd build-vtk && "${xvfb[@]}" ctest -j2 --output-on-failure -LE 'core|fuzz') ;;
  *) echo "usage: $0 [build|demo|test|vtk|sanitizers|benchmark [sizes]]" >&2; exit 2 ;;
esac
