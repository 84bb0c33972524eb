#!/usr/bin/env bash
# One distributed run checked against the one-process run: TestMPI.py under mpiexec writes the
# pieces, CheckDistributed (CheckDistributedVoronoi for "voronoi") reads them back in one process.
# usage: RunMPI.sh <ranks> <mpiexec> <pvbatch> <plugin> <checker> <output dir> <kind> <distribution> [alpha | voronoi]
set -euo pipefail
ranks=$1 mpiexec=$2 pvbatch=$3 plugin=$4 checker=$5 outdir=$6 kind=$7 distribution=$8 alpha=${9:-0}
out="$outdir/mpi-$kind-$distribution-$alpha-$ranks.pvtu"
log=$("$mpiexec" -np "$ranks" --allow-run-as-root --oversubscribe "$pvbatch" --mpi \
  "$(dirname "$0")/TestMPI.py" "$plugin" "$out" "$kind" "$distribution" - "$alpha" 2>&1) || { echo "$log"; exit 1; }
echo "$log"
volume=$(echo "$log" | sed -n 's/^TestMPI: volume \([^ ]*\) on .*/\1/p')
if [ "$alpha" = voronoi ]; then
  "$checker" "$out" "$kind" $(echo "$log" | sed -n 's/^TestMPI: faces \([^ ]*\) area \([^ ]*\)$/\1 \2/p')
else
  "$checker" "$out" "$volume" "$alpha"
fi
