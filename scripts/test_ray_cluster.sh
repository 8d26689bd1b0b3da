#!/usr/bin/env bash
# One scan across a Ray cluster, tested on this machine (scripts/test.sh's `ray
# cluster` section): a cluster of two nodes of one CPU each (`ray start --head` and
# `ray start --address`, on free ports, in a temporary folder of their own), then
# crates/primdecomp-py/tests/ray_cluster.py as the driver: the result equals the CLI's
# `--tiles K` file byte for byte, both nodes ran tiles, a rerun with the cache runs
# none, a corrupted cached tile is run again.
#
#   scripts/test_ray_cluster.sh VENV CLI INPUT.ply WORK_DIR
#
# VENV holds the installed wheel and ray. The cluster is always stopped on exit: the
# processes of this cluster only (found by its temporary folder, which every one of
# them names), not every Ray process of the machine as `ray stop` would.
set -uo pipefail
venv=$(cd "$1" && pwd) cli=$2 input=$3 work=$4
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$work"
# Ray's socket paths must fit in 107 bytes: a short folder.
ray_dir=$(mktemp -d /tmp/pdray.XXXXXX)
started=$SECONDS

ours() { # the pids of this cluster's processes
  grep -l -s -a -F "$ray_dir" /proc/[0-9]*/cmdline 2>/dev/null | cut -d/ -f3 | grep -vx "$$" || true
}
stop_cluster() {
  local pids
  pids=$(ours)
  # shellcheck disable=SC2086
  [ -n "$pids" ] && kill $pids 2>/dev/null
  for _ in 1 2 3 4 5 6 7 8 9 10; do
    pids=$(ours)
    [ -z "$pids" ] && break
    sleep 0.5
  done
  # shellcheck disable=SC2086
  [ -n "$pids" ] && kill -9 $pids 2>/dev/null
  rm -rf "$ray_dir"
}
trap stop_cluster EXIT
# A cluster on the loopback for this test alone: no token (Ray's default for `ray
# start --head` is token authentication, which a real cluster keeps, see README.md).
export RAY_AUTH_MODE=disabled

# Free ports for the head (GCS, node manager, object manager, agents, metrics) and the
# second node; worker ports 0 = chosen by the system.
read -r gcs n1 o1 a1 g1 m1 r1 n2 o2 a2 g2 m2 r2 < <("$venv/bin/python" - <<'EOF'
import socket
socks = [socket.socket() for _ in range(13)]
for s in socks:
    s.bind(("127.0.0.1", 0))
print(*[s.getsockname()[1] for s in socks])
EOF
)
common=(--num-cpus 1 --node-ip-address 127.0.0.1 --min-worker-port 0 --max-worker-port 0 --disable-usage-stats)
echo "-- ray start --head --port $gcs (one CPU) in $ray_dir"
"$venv/bin/ray" start --head --port "$gcs" "${common[@]}" --include-dashboard false --temp-dir "$ray_dir" \
  --node-manager-port "$n1" --object-manager-port "$o1" --dashboard-agent-listen-port "$a1" \
  --dashboard-agent-grpc-port "$g1" --metrics-export-port "$m1" --runtime-env-agent-port "$r1" \
  >"$work/head.log" 2>&1 || { cat "$work/head.log"; echo "FAILED: ray start --head"; exit 1; }
echo "-- ray start --address 127.0.0.1:$gcs (one CPU)"
"$venv/bin/ray" start --address "127.0.0.1:$gcs" "${common[@]}" --temp-dir "$ray_dir" \
  --node-manager-port "$n2" --object-manager-port "$o2" --dashboard-agent-listen-port "$a2" \
  --dashboard-agent-grpc-port "$g2" --metrics-export-port "$m2" --runtime-env-agent-port "$r2" \
  >"$work/node.log" 2>&1 || { cat "$work/node.log"; echo "FAILED: ray start --address"; exit 1; }
echo "-- the cluster is up after $(( SECONDS - started )) s; the driver:"
(cd /tmp && RAY_ADDRESS= "$venv/bin/python" "$root/crates/primdecomp-py/tests/ray_cluster.py" \
  --address "127.0.0.1:$gcs" --cli "$cli" --input "$input" --work "$work")
status=$?
echo "-- $(( SECONDS - started )) s in all (cluster start, driver, checks)"
exit $status
