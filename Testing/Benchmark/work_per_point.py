"""Instructions and cache misses per inserted point, per phase, for Core and for CGAL, counted by
cachegrind: deterministic, the same on any machine, where a shared machine's clock is not.

usage: python3 work_per_point.py <WorkPerPoint program> [sizes=100000,1000000] [kinds=cube]
prints a markdown table. The caches are set, not read from the machine: 32 KiB 8-way level 1
(instructions and data), and an 8 MiB 16-way last level, a core's share of a server's L3. A phase
is the set of functions whose names match it below; code the compiler inlined counts in the
function it was inlined into: CGAL's insertion loop (its conflict search's walk over the cells, the
locate's steps) is inlined into the driver's function and counts as "other". Point generation (the
same for both) is left out; "other" is also what no phase names (memory management, the rest).
"""
import os
import re
import subprocess
import sys
import tempfile

PHASES = {
    "core": [
        ("sort", r"InsertionOrder|planInsertion|hilbert|Hilbert|brio|radixSort|perturbationKey|"
                 r"Impl::keys|finiteBounds|Frame|frameOf|normaliz|skipClosePoints"),
        ("locate", r"Inserter::walk|Inserter::locate|startTet|regionStart|BackgroundGrid|"
                   r"nearestInserted|mayEnter|orderByDistance|hullFaceToward"),
        ("cavity", r"digCavity|ghostInConflict|openConflict|Predicates::|insideBeyond|inSphere|"
                   r"orient3d|symbolic|Expansion|correctCavity|undoCavity|makeRoomInCavityLists"),
        ("fill", r"fillCavity|createAndLink|linkAroundEdge|linkByRotation|SlotPool|insertAs|"
                 r"BulkAllocator|releasePages"),
    ],
    "cgal": [
        ("sort", r"spatial_sort|hilbert_sort|Hilbert_sort|Multiscale_sort|random_shuffle"),
        ("locate", r"::locate|inexact_locate|exact_locate"),
        ("cavity", r"side_of_oriented_sphere|side_of_sphere|Orientation_3|orientation|"
                   r"find_conflicts|priv_push_back"),
        ("fill", r"insert_in_hole|insert_in_small_hole|create_star|Compact_container"),
    ],
}
INPUT = r"fd3test::|generate|mersenne|normal_distribution|uniform_real|generate_canonical|" \
        r"randomDirection"
EVENTS = ["Ir", "D1mr", "D1mw", "DLmr", "DLmw"]


def counts(program, method, kind, n):
    """Per function name: cachegrind's counts of one run."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "cg.out")
        subprocess.run(["valgrind", "--tool=cachegrind", "--cache-sim=yes",
                        "--I1=32768,8,64", "--D1=32768,8,64", "--LL=8388608,16,64",
                        f"--cachegrind-out-file={out}", program, method, kind, str(n)],
                       check=True, capture_output=True)
        events, functions = [], {}
        name = None
        with open(out) as data:
            for line in data:
                if line.startswith("events:"):
                    events = line.split()[1:]
                elif line.startswith("fn="):
                    name = line[3:].strip()
                elif line[:1].isdigit() and name is not None:
                    values = [int(v) for v in line.split()[1:]]
                    total = functions.setdefault(name, [0] * len(events))
                    for i, v in enumerate(values):
                        total[i] += v
        return {f: dict(zip(events, v)) for f, v in functions.items()}


def by_phase(functions, method):
    phases = {name: dict.fromkeys(EVENTS, 0) for name, _ in PHASES[method]}
    phases["other"] = dict.fromkeys(EVENTS, 0)
    for function, values in functions.items():
        if re.search(INPUT, function):
            continue
        phase = next((p for p, pattern in PHASES[method] if re.search(pattern, function)), "other")
        for e in EVENTS:
            phases[phase][e] += values.get(e, 0)
    return phases


def main():
    program = sys.argv[1]
    sizes = [int(float(s)) for s in (sys.argv[2] if len(sys.argv) > 2 else "100000,1000000").split(",")]
    kinds = (sys.argv[3] if len(sys.argv) > 3 else "cube").split(",")
    print("Per inserted point, counted by cachegrind (level 1: 32 KiB 8-way; last level: 8 MiB "
          "16-way). D1: level-1 data misses (reads and writes); LL: last-level data misses.\n")
    print("| points | n | method | phase | instructions | D1 misses | LL misses |")
    print("|---|---:|---|---|---:|---:|---:|")
    for kind in kinds:
        for n in sizes:
            for method in ("core", "cgal"):
                try:
                    phases = by_phase(counts(program, method, kind, n), method)
                except subprocess.CalledProcessError:
                    print(f"| {kind} | {n} | {method} | not built with it | | | |")
                    continue
                total = {e: sum(p[e] for p in phases.values()) for e in EVENTS}
                for phase, v in list(phases.items()) + [("total", total)]:
                    print(f"| {kind} | {n} | {'Core' if method == 'core' else 'CGAL'} | {phase} | "
                          f"{v['Ir'] / n:.0f} | {(v['D1mr'] + v['D1mw']) / n:.1f} | "
                          f"{(v['DLmr'] + v['DLmw']) / n:.2f} |", flush=True)


main()
