#!/usr/bin/env bash
# Test the multi-host deployment (deploy/README.md, "Many hosts") for real on
# this one machine: three "hosts" are Linux network namespaces on a private
# bridge, and the experiment runs across them exactly as the README says.
#
#   adv-sim  10.213.47.10   a zenoh router (the rendezvous, tcp/10.213.47.10:7447,
#                           `coordinator router`), env-server and, once the
#                           agents are up, the coordinator
#   adv-a    10.213.47.11   agents 0 and 1
#   adv-b    10.213.47.12   agent 2
#   adv-net  (no address)   the bridge adv-br joining the three veth pairs
#
# The bridge lives in a fourth namespace, so nothing is added to the root
# namespace (no interface, no route, no firewall interplay) and no packet can
# leave the machine: 10.213.47.0/24 exists only inside these namespaces.
#
# Pass: the coordinator exits 0; summary.json has comm.advice_requests
# > 0 and comm.advice_replies_received > 0; advice crossed hosts both ways
# (agent 2 on adv-b got replies, all from adv-a, and agents 0 and 1 got more
# replies than they sent requests, so agent 2 answered them); and both agents
# on adv-a had a direct TCP connection to adv-b while the experiment ran
# (advice goes agent to agent, not through env-server); and an agent started
# on adv-b without the experiment's secret is refused (exit 2, "cannot join
# the zenoh network"). Every process gets --secret-file and connects only to
# the router; the router is restarted while the experiment runs, and adv-b
# drops 5% of the packets it receives (nftables, where `nft` is installed):
# the run must still finish. It prints what the losses cost (advice requests
# without replies, actions played as Move) and which processes are still
# running after the coordinator has finished.
#
# With --tls, the TLS setup of deploy/tls/ on top: every process has its
# own certificate (deploy/tls/make-credentials.sh), links are QUIC (TLS 1.3)
# with mutual authentication and every process enforces zenoh's access
# control (QUIC, not zenoh's tls/ link, whose reader and writer race on one
# rustls connection: deploy/README.md, "TLS and access control"). Then a
# host holding the secret but a certificate of another authority is refused,
# and a coordinator started with an agent's own certificate cannot drive the
# experiment (its control queries are denied: exit 2, "did not answer" or
# "did not join", no results).
#
#   sudo deploy/netns-test.sh [--skip-if-unavailable] [--keep] [--listen-any] [--tls | --zenohd]
#
#   --skip-if-unavailable  not root / no `ip netns`: print "SKIP: <reason>"
#                          and exit 0 (without it: exit 1)
#   --keep                 keep the logs (one per process, and `ss` samples)
#                          and results even on pass (always kept on failure)
#   --listen-any           listen on 0.0.0.0 (every interface) as the
#                          README's own commands do, instead of each host's
#                          test address
#   --tls                  certificates, QUIC with mutual TLS and access
#                          control (above); direct agent links are shown by
#                          the packets adv-a sends adv-b (nft counter), as
#                          `ss` cannot tie UDP sockets to peers
#   --zenohd               the router is zenoh's own zenohd (on PATH, or
#                          ZENOHD; `cargo install zenohd --version 1.10.2`)
#                          with deploy/zenoh-router.json5's settings, instead
#                          of `coordinator router`
#
# Environment: BIN (default target/release), RUST_LOG (default info, for
# every process), TIMEOUT (coordinator time limit in s, default 300), ZENOHD
# (default: zenohd on PATH).
# Exit status: 0 pass (or skip with --skip-if-unavailable), 1 fail/unavailable,
# 130/143 interrupted. Everything it creates is removed on exit, whatever
# happens; leftovers of an earlier run are removed first.
set -euo pipefail

skip_ok=0
keep=0
listen_any=0
tls=0
zenohd=0
for arg in "$@"; do
    case $arg in
        --skip-if-unavailable) skip_ok=1 ;;
        --keep) keep=1 ;;
        --listen-any) listen_any=1 ;;
        --tls) tls=1 ;;
        --zenohd) zenohd=1 ;;
        -h | --help)
            sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
            exit 0
            ;;
        *)
            echo "unknown argument: $arg (see --help)" >&2
            exit 1
            ;;
    esac
done

cd "$(dirname "$0")/.."
BIN=${BIN:-$PWD/target/release}
LOG_LEVEL=${RUST_LOG:-info}
TIMEOUT=${TIMEOUT:-300}

# The test network. Names are fixed so that a rerun finds and removes the
# leftovers of an interrupted run.
NS_SIM=adv-sim
NS_A=adv-a
NS_B=adv-b
NS_NET=adv-net
ALL_NS=("$NS_SIM" "$NS_A" "$NS_B" "$NS_NET")
SIM_IP=10.213.47.10
A_IP=10.213.47.11
B_IP=10.213.47.12
PORT=7447
EXPERIMENT=netns
LOSS_PERCENT=5
SCHEME=tcp
SS_PROTO=t # what `ss` lists: TCP, or UDP for QUIC
if [ "$tls" = 1 ]; then SCHEME=quic SS_PROTO=u; fi
RENDEZVOUS=$SCHEME/$SIM_IP:$PORT

# The experiment (small: about a minute at most). The advice timeout is
# 25 ms, not the default 5: the test checks that advice crosses hosts, and
# a debug build over QUIC on a busy two-core machine answers in 5 ms or
# more half the time.
RUN_ARGS=(--algorithm adhoc-td --runs 1 --episodes 200 --eval-every 50 --eval-episodes 20
    --advice-timeout-ms 25)

say() { printf '[netns-test] %s\n' "$*"; }

# Not root, or no working `ip netns`: SKIP, exit 0 only if allowed.
unavailable() {
    echo "SKIP: $1"
    if [ "$skip_ok" = 1 ]; then exit 0; fi
    exit 1
}

fail() {
    echo "FAIL: $1"
    exit 1
}

# --- processes -------------------------------------------------------------

pids=()  # every process started (ip netns exec execs, so these are the programs)
names=() # their names, same order

# start NAME NAMESPACE COMMAND...: runs COMMAND in NAMESPACE in the
# background, output in $work/NAME.log.
start() {
    local name=$1 ns=$2
    shift 2
    ip netns exec "$ns" env RUST_LOG="$LOG_LEVEL" "$@" >"$work/$name.log" 2>&1 &
    pids+=("$!")
    names+=("$name")
}

pid_of() {
    local i
    for i in "${!names[@]}"; do
        if [ "${names[$i]}" = "$1" ]; then echo "${pids[$i]}"; fi
    done
}

# Kills every process this script started (TERM, then KILL after 5 s), then,
# as a safety net, whatever still runs inside the test namespaces (only
# processes of this script, or of an earlier run of it, can be there).
stop_processes() {
    local pid ns deadline
    for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
    deadline=$((SECONDS + 5))
    for pid in "${pids[@]}"; do
        while kill -0 "$pid" 2>/dev/null && [ "$SECONDS" -lt "$deadline" ]; do sleep 0.1; done
        kill -KILL "$pid" 2>/dev/null || true
    done
    for ns in "${ALL_NS[@]}"; do
        for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
    done
    wait 2>/dev/null || true
}

# --- network ---------------------------------------------------------------

ns_exists() { ip netns list 2>/dev/null | awk '{print $1}' | grep -qx "$1"; }

# Deleting a namespace deletes its interfaces: the bridge, and both ends of
# every veth pair (a veth dies with its peer).
delete_namespaces() {
    local ns pid
    for ns in "${ALL_NS[@]}" adv-probe; do
        ns_exists "$ns" || continue
        for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
        ip netns del "$ns" 2>/dev/null || true
    done
}

# Can this machine do what the test needs: namespaces, a veth pair, a bridge?
probe() {
    local err
    if ! err=$(ip netns add adv-probe 2>&1); then
        unavailable "cannot create a network namespace (ip netns add: ${err:-no message})"
    fi
    if ! err=$({ ip -n adv-probe link add probe-br type bridge &&
        ip -n adv-probe link add probe0 type veth peer name probe1; } 2>&1); then
        ip netns del adv-probe 2>/dev/null || true
        unavailable "cannot create a bridge or veth pair in a namespace: ${err:-no message}"
    fi
    ip netns del adv-probe
}

# host NAMESPACE ADDRESS BRIDGE-PORT: a namespace with eth0 = ADDRESS/24,
# the other end of its veth plugged into the bridge.
host() {
    local ns=$1 ip=$2 port=$3
    ip netns add "$ns"
    ip -n "$ns" link set lo up
    ip link add eth0 netns "$ns" type veth peer name "$port" netns "$NS_NET"
    ip -n "$NS_NET" link set "$port" master adv-br up
    ip -n "$ns" addr add "$ip/24" dev eth0
    ip -n "$ns" link set eth0 up
}

setup_network() {
    ip netns add "$NS_NET"
    ip -n "$NS_NET" link set lo up
    ip -n "$NS_NET" link add adv-br type bridge
    ip -n "$NS_NET" link set adv-br up
    host "$NS_SIM" "$SIM_IP" to-sim
    host "$NS_A" "$A_IP" to-a
    host "$NS_B" "$B_IP" to-b
}

# --- cleanup ---------------------------------------------------------------

work=""
cleanup() {
    local rc=$?
    trap - EXIT INT TERM
    stop_processes
    delete_namespaces
    if [ -n "$work" ]; then
        if [ "$rc" = 0 ] && [ "$keep" = 0 ]; then
            rm -rf "$work"
        else
            say "logs and results kept in $work"
        fi
    fi
    exit "$rc"
}

# --- checks before touching anything ---------------------------------------

[ "$(id -u)" = 0 ] || unavailable "not root (network namespaces need CAP_SYS_ADMIN and CAP_NET_ADMIN)"
command -v ip >/dev/null || unavailable "iproute2's ip is not installed"
ip netns list >/dev/null 2>&1 || unavailable "ip netns is not supported by this ip ($(ip -V 2>&1))"
command -v ss >/dev/null || unavailable "iproute2's ss is not installed"
for tool in jq timeout; do
    command -v "$tool" >/dev/null || fail "$tool is needed by this test"
done
for exe in env-server agent coordinator; do
    [ -x "$BIN/$exe" ] || fail "$BIN/$exe missing: cargo build --release --workspace"
done
if [ "$zenohd" = 1 ]; then
    [ "$tls" = 0 ] || fail "--zenohd goes without --tls (the TLS setup configures coordinator router)"
    ZENOHD=${ZENOHD:-$(command -v zenohd || true)}
    [ -x "$ZENOHD" ] || fail "zenohd not found: cargo install zenohd --version 1.10.2, or set ZENOHD"
fi

trap cleanup EXIT
trap 'echo "FAIL: interrupted"; exit 130' INT
trap 'echo "FAIL: terminated"; exit 143' TERM

delete_namespaces # leftovers of an interrupted run
probe
work=$(mktemp -d "${TMPDIR:-/tmp}/adv-netns-test.XXXXXX")

# --- the experiment --------------------------------------------------------

say "network: $NS_SIM=$SIM_IP $NS_A=$A_IP $NS_B=$B_IP on bridge adv-br in $NS_NET"
setup_network

# What each process listens on: its host's test address, or (--listen-any)
# every interface of its host, as in the README.
listen_on() { if [ "$listen_any" = 1 ]; then echo "$SCHEME/0.0.0.0:$2"; else echo "$SCHEME/$1:$2"; fi; }

# The experiment's secret: every process gets the file (on real hosts, a
# copy of it, mode 600).
"$BIN/coordinator" secret "$work/secret"

# With --tls, every process's certificate and zenoh configuration, made as
# deploy/README.md says; credentials NAME gives the flag that uses NAME's.
if [ "$tls" = 1 ]; then
    command -v openssl >/dev/null || fail "openssl is needed for --tls"
    bash deploy/tls/make-credentials.sh "$work/tls" "$EXPERIMENT" router="$SIM_IP" \
        env-server="$SIM_IP" coordinator="$SIM_IP" agent-0="$A_IP" agent-1="$A_IP" agent-2="$B_IP" >/dev/null
    say "TLS with mutual authentication and access control: credentials in $work/tls"
fi
credentials() { if [ "$tls" = 1 ]; then echo "--zenoh-config $work/tls/$1/zenoh.json5"; fi; }

# router NAME: starts the router and waits until it listens.
router() {
    say "router ($1) on $NS_SIM, listening on $(listen_on "$SIM_IP" "$PORT")"
    if [ "$zenohd" = 1 ]; then
        # deploy/zenoh-router.json5 with this test's endpoint and secret.
        sed -e "s|tcp/0.0.0.0:7447|$(listen_on "$SIM_IP" "$PORT")|" \
            -e "s|/etc/adv/secret|$work/secret|" deploy/zenoh-router.json5 >"$work/zenohd.json5"
        start "$1" "$NS_SIM" "$ZENOHD" --config "$work/zenohd.json5"
    else
        start "$1" "$NS_SIM" "$BIN/coordinator" router --listen "$(listen_on "$SIM_IP" "$PORT")" \
            --secret-file "$work/secret" $(credentials router)
    fi
    for _ in $(seq 100); do
        [ -n "$(ip netns exec "$NS_SIM" ss -H"$SS_PROTO"ln "sport = :$PORT")" ] && return
        kill -0 "$(pid_of "$1")" 2>/dev/null || fail "the router exited (see $work/$1.log)"
        sleep 0.1
    done
    fail "the router does not listen on $RENDEZVOUS"
}
router router

say "env-server on $NS_SIM, listening on $(listen_on "$SIM_IP" 0), connecting to $RENDEZVOUS"
start env-server "$NS_SIM" "$BIN/env-server" serve --experiment "$EXPERIMENT" \
    --listen "$(listen_on "$SIM_IP" 0)" --connect "$RENDEZVOUS" --secret-file "$work/secret" \
    $(credentials env-server)
# Both agent hosts reach the rendezvous over the bridge (a bare TCP connect,
# closed at once; no ping needed; QUIC's UDP has no such check).
for ns in "$NS_A" "$NS_B"; do
    [ "$SS_PROTO" = t ] || break
    ip netns exec "$ns" timeout 5 bash -c "exec 3<>/dev/tcp/$SIM_IP/$PORT" ||
        fail "$ns cannot reach $RENDEZVOUS over the test bridge"
done

say "agents 0, 1 on $NS_A and 2 on $NS_B, listening on $(listen_on "<host>" 0), connecting to $RENDEZVOUS"
agent() { # ID NAMESPACE ADDRESS
    start "agent-$1" "$2" "$BIN/agent" --experiment "$EXPERIMENT" --id "$1" --team-size 3 \
        --listen "$(listen_on "$3" 0)" --connect "$RENDEZVOUS" --secret-file "$work/secret" \
        $(credentials "agent-$1")
}
agent 0 "$NS_A" "$A_IP"
agent 1 "$NS_A" "$A_IP"
agent 2 "$NS_B" "$B_IP"

# Who is connected to whom: sampled every 0.2 s while the experiment runs
# (the run is short, and whether the processes outlive the coordinator is
# reported separately below).
connections() { ip netns exec "$1" ss -Htnp state established 2>/dev/null || true; }
# QUIC runs over unconnected UDP sockets, which `ss` cannot tie to a peer:
# count what adv-a sends to adv-b instead (only agents live on either).
if [ "$SS_PROTO" = u ] && command -v nft >/dev/null; then
    printf 'table inet watch { chain out { type filter hook output priority 0; ip daddr %s counter; }; }\n' \
        "$B_IP" | ip netns exec "$NS_A" nft -f -
fi
(
    while :; do
        for ns in "$NS_SIM" "$NS_A" "$NS_B"; do connections "$ns" >>"$work/ss-$ns.txt"; done
        sleep 0.2
    done
) &
pids+=("$!")
names+=(ss-sampler)

# adv-b loses packets: every one it receives is dropped with probability
# LOSS_PERCENT % (nftables' random number; tc netem needs a kernel module
# this test cannot count on).
if command -v nft >/dev/null; then
    printf 'table inet loss { chain input { type filter hook input priority 0; numgen random mod 100 < %s drop; }; }\n' \
        "$LOSS_PERCENT" | ip netns exec "$NS_B" nft -f -
    say "$NS_B drops $LOSS_PERCENT% of the packets it receives"
else
    say "nft is not installed: no packet loss on $NS_B (apt-get install nftables)"
fi

say "coordinator on $NS_SIM: ${RUN_ARGS[*]}"
start coordinator "$NS_SIM" timeout "$TIMEOUT" "$BIN/coordinator" run --transport zenoh --attach \
    --experiment "$EXPERIMENT" --connect "$RENDEZVOUS" --listen "$(listen_on "$SIM_IP" 0)" \
    --secret-file "$work/secret" $(credentials coordinator) \
    "${RUN_ARGS[@]}" --quiet --out "$work/out"
started=$SECONDS
# The rendezvous goes away mid-run and comes back.
sleep 2
if kill -0 "$(pid_of coordinator)" 2>/dev/null; then
    say "restarting the router mid-run"
    kill -TERM "$(pid_of router)"
    wait "$(pid_of router)" || true
    sleep 1
    router router-2
else
    say "the coordinator ended before the router restart"
fi
# `wait` in the background, so that Ctrl-C runs the cleanup at once.
coordinator_rc=0
wait "$(pid_of coordinator)" || coordinator_rc=$?
say "coordinator exited $coordinator_rc after $((SECONDS - started)) s$([ "$coordinator_rc" != 124 ] || echo " (killed: TIMEOUT=$TIMEOUT s)")"
kill "$(pid_of ss-sampler)" 2>/dev/null || true
ip netns exec "$NS_B" nft delete table inet loss 2>/dev/null || true

# A host without the secret (and, with --tls, without a certificate)
# cannot join: an agent on adv-b started without it is refused by the
# rendezvous (exit 2, "cannot join").
intruder_rc=0
ip netns exec "$NS_B" timeout 30 "$BIN/agent" --experiment "$EXPERIMENT" --id 2 --team-size 3 \
    --listen "tcp/$B_IP:0" --connect "$RENDEZVOUS" --no-auth \
    >"$work/intruder.log" 2>&1 || intruder_rc=$?
grep -q "cannot join the zenoh network" "$work/intruder.log" && [ "$intruder_rc" = 2 ] ||
    fail "a host without the secret was not refused (rc $intruder_rc, see $work/intruder.log)"
say "a host without the secret is refused: $(cat "$work/intruder.log")"

if [ "$tls" = 1 ]; then
    # The secret, but a certificate of another authority: refused.
    bash deploy/tls/make-credentials.sh "$work/foreign" "$EXPERIMENT" agent-2="$B_IP" >/dev/null
    intruder_rc=0
    ip netns exec "$NS_B" timeout 30 "$BIN/agent" --experiment "$EXPERIMENT" --id 2 --team-size 3 \
        --listen "$(listen_on "$B_IP" 0)" --connect "$RENDEZVOUS" --secret-file "$work/secret" \
        --zenoh-config "$work/foreign/agent-2/zenoh.json5" >"$work/foreign.log" 2>&1 || intruder_rc=$?
    grep -q "cannot join the zenoh network" "$work/foreign.log" && [ "$intruder_rc" = 2 ] ||
        fail "a certificate of another authority was not refused (rc $intruder_rc, see $work/foreign.log)"
    say "a certificate of another authority is refused: $(cat "$work/foreign.log")"
    # Agent 2's own credentials, used to drive the experiment: denied.
    intruder_rc=0
    ip netns exec "$NS_B" timeout 60 "$BIN/coordinator" run --transport zenoh --attach \
        --experiment "$EXPERIMENT" --connect "$RENDEZVOUS" --listen "$(listen_on "$B_IP" 0)" \
        --secret-file "$work/secret" $(credentials agent-2) --startup-timeout 10 \
        --algorithm adhoc-td --runs 1 --episodes 5 --quiet --out "$work/out-intruder" \
        >"$work/agent-as-coordinator.log" 2>&1 || intruder_rc=$?
    # Refused either way: its control queries are denied, or the tokens it
    # needs never reach it.
    grep -Eq "did not answer|did not join" "$work/agent-as-coordinator.log" && [ "$intruder_rc" = 2 ] &&
        [ ! -e "$work/out-intruder/summary.json" ] ||
        fail "an agent's certificate drove the experiment (rc $intruder_rc, see $work/agent-as-coordinator.log)"
    say "an agent's certificate cannot drive the experiment: $(cat "$work/agent-as-coordinator.log")"
fi

# The README says attached processes keep running for the next experiment:
# report which ones did (a second later).
sleep 1
after=()
for name in env-server agent-0 agent-1 agent-2; do
    if kill -0 "$(pid_of "$name")" 2>/dev/null; then
        after+=("$name running")
    else
        status=0
        wait "$(pid_of "$name")" || status=$?
        after+=("$name exited $status")
    fi
done
after_text=$(IFS=,; echo "${after[*]}")
say "after the coordinator: ${after_text//,/, }"

# adv-a and adv-b hold only agents, so every TCP connection between them is
# agent to agent, never through env-server. The pids on adv-a holding one:
a_to_b=$(awk -v b="$B_IP" '$4 ~ "^"b":" {print $5}' "$work/ss-$NS_A.txt" |
    { grep -o 'pid=[0-9]*' || true; } | cut -d= -f2 | sort -u | tr '\n' ' ')
# distinct connections (local and peer endpoints)
a_b_links=$(awk -v b="$B_IP" '$4 ~ "^"b":" {print $3, $4}' "$work/ss-$NS_A.txt" | sort -u | wc -l)

# --- verdict ---------------------------------------------------------------

summary=$work/out/summary.json
if [ "$coordinator_rc" != 0 ] || [ ! -s "$summary" ]; then
    for f in "$work"/*.log; do
        echo "--- $(basename "$f") (last lines)"
        tail -n 15 "$f"
    done
    fail "coordinator exit status $coordinator_rc$([ -s "$summary" ] || echo ', no summary.json')"
fi

num() { jq -r "$1 // 0" "$summary"; }
requests=$(num .comm.advice_requests)
replies=$(num .comm.advice_replies_received)
given=$(num .comm.advice_given)
b_requests=$(num '.comm.per_agent[2].advice_requests')
b_replies=$(num '.comm.per_agent[2].advice_replies_received')
b_given=$(num '.comm.per_agent[2].advice_given')
a_requests=$(num '[.comm.per_agent[0,1].advice_requests] | add')
a_replies=$(num '[.comm.per_agent[0,1].advice_replies_received] | add')
rtt=$(jq -r '.comm.advice_rtt_ms | "median \(.median) ms, p99 \(.p99) ms"' "$summary")
timed_out=$(num .comm.actions_timed_out)
gt0() { jq -en --argjson v "$1" '$v > 0' >/dev/null; }

say "team: requests $requests, replies $replies, advice given $given; rtt $rtt"
say "agents 0+1 ($NS_A): requests $a_requests, replies $a_replies (from each other and from $NS_B)"
say "agent 2 ($NS_B): requests $b_requests, replies $b_replies (from $NS_A), advice given $b_given (to $NS_A)"
say "losses: actions played as Move after the step timeout $timed_out; agent 2's requests without a reply from each advisor: $(jq -n --argjson q "$b_requests" --argjson r "$b_replies" '2 * $q - $r')"
if [ "$SS_PROTO" = t ]; then
    say "direct TCP $NS_A<->$NS_B: $a_b_links distinct connection(s) seen; agents on $NS_A in them: pids ${a_to_b:-none}" \
        "(agent 0 = $(pid_of agent-0), agent 1 = $(pid_of agent-1))"
fi

problems=()
gt0 "$requests" || problems+=("no advice requests")
gt0 "$replies" || problems+=("no advice replies")
gt0 "$b_replies" || problems+=("agent 2 on $NS_B got no reply from $NS_A")
# Agents 0 and 1 each ask their two teammates; a request gets at most one
# reply per advisor, so more replies than requests means agent 2 (adv-b)
# answered some.
jq -en --argjson r "$a_replies" --argjson q "$a_requests" '$r > $q' >/dev/null ||
    problems+=("agent 2 on $NS_B never answered $NS_A (agents 0+1: $a_requests requests, $a_replies replies)")
if [ "$SS_PROTO" = t ]; then
    for id in 0 1; do
        [[ " $a_to_b " == *" $(pid_of "agent-$id") "* ]] ||
            problems+=("agent $id on $NS_A has no direct connection to $NS_B")
    done
elif command -v nft >/dev/null; then
    a_b_packets=$(ip netns exec "$NS_A" nft list chain inet watch out | grep -o 'packets [0-9]*' | cut -d' ' -f2)
    say "QUIC: $NS_A sent ${a_b_packets:-0} packets to $NS_B directly"
    [ "${a_b_packets:-0}" -gt 0 ] || problems+=("$NS_A sent nothing to $NS_B: no direct agent links")
else
    say "nft is not installed: direct QUIC links between $NS_A and $NS_B are not checked"
fi

numbers="requests=$requests replies=$replies given=$given agent2(replies=$b_replies given=$b_given) a<->b-$([ "$SS_PROTO" = t ] && echo "links=$a_b_links" || echo "packets=${a_b_packets:-?}")"
if [ "${#problems[@]}" -gt 0 ]; then
    fail "$(IFS=';'; echo "${problems[*]}") [$numbers]"
fi
echo "PASS: netns multi-host adhoc-td over $SCHEME$([ "$zenohd" = 0 ] || echo " through zenohd"), coordinator exit 0, $numbers"
