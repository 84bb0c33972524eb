#!/usr/bin/env bash
# A pvpython client connected to a pvserver on 2 MPI ranks runs the filter; the pieces the server
# writes are checked against the one-process run.
# usage: RunClientServer.sh <mpiexec> <pvserver> <pvpython> <plugin> <CheckDistributed> <output dir>
set -euo pipefail
mpiexec=$1 pvserver=$2 pvpython=$3 plugin=$4 checker=$5 outdir=$6
port=$((20000 + RANDOM % 20000))
"$mpiexec" -np 2 --allow-run-as-root --oversubscribe "$pvserver" --server-port=$port &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
out="$outdir/client-server.pvtu"
log=$("$pvpython" "$(dirname "$0")/TestMPI.py" "$plugin" "$out" clusters scattered $port 2>&1) || { echo "$log"; exit 1; }
echo "$log"
volume=$(echo "$log" | sed -n 's/^TestMPI: volume \([^ ]*\) on 2 ranks/\1/p')
"$checker" "$out" "$volume"
