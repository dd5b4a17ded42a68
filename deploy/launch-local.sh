#!/usr/bin/env bash
# Launch a whole experiment on this host: env-server, N agent processes and a
# coordinator that attaches to them, all over loopback zenoh.
#
#   deploy/launch-local.sh [coordinator run options...]
#   e.g. deploy/launch-local.sh --algorithm adhoc-td --runs 5 --episodes 1000 --out results/local
#
# Environment: AGENTS (default 3), PORT (default 7447), EXPERIMENT (default
# local-<pid>), BIN (default target/release).
set -euo pipefail
cd "$(dirname "$0")/.."
AGENTS=${AGENTS:-3}
PORT=${PORT:-7447}
EXPERIMENT=${EXPERIMENT:-local-$$}
BIN=${BIN:-target/release}
[ -x "$BIN/coordinator" ] || cargo build --release --workspace
pids=()
# The experiment's secret, in a directory only this user can enter.
secret_dir=$(mktemp -d)
SECRET=$secret_dir/secret
cleanup() { kill "${pids[@]}" 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$secret_dir"; }
trap cleanup EXIT INT TERM
"$BIN/coordinator" secret "$SECRET"
"$BIN/env-server" serve --experiment "$EXPERIMENT" --listen "tcp/127.0.0.1:$PORT" \
    --secret-file "$SECRET" &
pids+=($!)
for ((i = 0; i < AGENTS; i++)); do
    "$BIN/agent" --experiment "$EXPERIMENT" --id "$i" --team-size "$AGENTS" \
        --connect "tcp/127.0.0.1:$PORT" --secret-file "$SECRET" &
    pids+=($!)
done
"$BIN/coordinator" run --transport zenoh --attach --experiment "$EXPERIMENT" \
    --connect "tcp/127.0.0.1:$PORT" --secret-file "$SECRET" --offense "$AGENTS" "$@"
