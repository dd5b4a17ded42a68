#!/usr/bin/env bash
# Credentials for an experiment across hosts on a network you do not trust:
# TLS with mutual authentication and zenoh's access control (deploy/README.md,
# "TLS and access control").
#
#   deploy/tls/make-credentials.sh OUT_DIR EXPERIMENT NAME=ADDRESS...
#
# NAME is a process's role: router, coordinator, env-server or agent-<id>.
# ADDRESS is the IP address or DNS name that host is reached at (its
# certificate is valid for it). It writes, with openssl:
#
#   OUT_DIR/ca.key, ca.srl    the experiment's certificate authority: keep it
#                             here (mode 600), never copy it to a host
#   OUT_DIR/NAME/ca.pem       its certificate, which every process trusts
#   OUT_DIR/NAME/cert.pem     NAME's certificate (common name NAME), signed by it
#   OUT_DIR/NAME/key.pem      NAME's private key (mode 600)
#   OUT_DIR/NAME/zenoh.json5  NAME's zenoh configuration (--zenoh-config): TLS
#                             both ways with these files, and the access
#                             control below
#
# Copy OUT_DIR/NAME to NAME's host at the same absolute path (the
# configuration names its files by absolute path; PREFIX=/etc/adv writes
# /etc/adv/NAME/... into it instead). Every process then listens and connects
# with quic/ endpoints (QUIC is TLS 1.3 over UDP; zenoh's tls/ links take the
# same files but close under load, see deploy/README.md) and refuses a peer
# whose certificate the experiment's authority did not sign.
#
# Access control (every process enforces it on what its peers send it; the
# common name of the peer's certificate says who sent it; anything not listed
# is denied):
#   env-server  publishes observations (obs/*), subscribes to actions,
#               answers control queries addressed to the server
#   agent-<id>  publishes its own actions (act/<id>) and shared knowledge,
#               subscribes to its own observations and shares, asks any
#               agent for advice, answers advice and control queries
#               addressed to it
#   coordinator sends control queries (ctl/**)
#   router      forwards all of the above (it enforces the same rules on
#               what it receives)
#   all         declare their own liveliness token and watch the others'
# So a stolen agent certificate cannot stop env-server, act for another agent
# or forge observations. Certificates are valid for 30 days (DAYS=...).
set -euo pipefail

if [ $# -lt 3 ]; then
    sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit 2
fi
out=$1
experiment=$2
shift 2
[[ $experiment =~ ^[A-Za-z0-9_-]{1,64}$ ]] ||
    { echo "invalid experiment name '$experiment': use 1 to 64 letters, digits, '-' or '_'" >&2; exit 2; }
command -v openssl >/dev/null || { echo "openssl is needed (apt-get install openssl)" >&2; exit 2; }
days=${DAYS:-30}
mkdir -p "$out"
out=$(cd "$out" && pwd)
prefix=${PREFIX:-$out}
umask 077

# The authority.
if [ ! -f "$out/ca.key" ]; then
    openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -days "$days" \
        -subj "/CN=adv-$experiment-ca" -keyout "$out/ca.key" -out "$out/ca.pem" 2>/dev/null
fi

# rule ID MESSAGES KEYS [FLOW]: one allow rule, by default on what a peer
# sends (ingress).
rule() {
    printf '      { id: "%s", permission: "allow", flows: ["%s"], messages: [%s], key_exprs: [%s] },\n' \
        "$1" "${4:-ingress}" "$2" "$3"
}
all_messages='"put", "delete", "declare_subscriber", "query", "reply", "declare_queryable", "liveliness_token", "liveliness_query", "declare_liveliness_subscriber"'
# The rule ids of a role.
rules_of() {
    case $1 in
        router) echo '"forward"' ;;
        coordinator) echo '"alive-watch", "coordinator-alive", "coordinator-control"' ;;
        env-server) echo '"alive-watch", "server-alive", "server-observe", "server-act", "server-control"' ;;
        agent-*) local i=${1#agent-}
            echo "\"alive-watch\", \"agent-$i-alive\", \"agent-$i-send\", \"agent-$i-receive\", \"agent-$i-ask\", \"agent-$i-answer\"" ;;
    esac
}

names=()
for spec in "$@"; do
    name=${spec%%=*}
    address=${spec#*=}
    [ "$name" != "$spec" ] && [ -n "$address" ] || { echo "expected NAME=ADDRESS, got '$spec'" >&2; exit 2; }
    [[ $name =~ ^(router|coordinator|env-server|agent-[0-9]{1,3})$ ]] ||
        { echo "unknown role '$name': expected router, coordinator, env-server or agent-<id>" >&2; exit 2; }
    names+=("$name")
done

# The access control every process gets (all the roles named).
p="adv/$experiment"
acl() {
    echo '  access_control: {'
    echo '    enabled: true,'
    echo '    default_permission: "deny",'
    echo '    rules: ['
    rule egress "$all_messages" "\"$p/**\"" egress
    rule forward "$all_messages" "\"$p/**\""
    rule alive-watch '"liveliness_query", "declare_liveliness_subscriber"' "\"$p/alive/**\""
    rule coordinator-alive '"liveliness_token"' "\"$p/alive/coordinator\""
    rule coordinator-control '"query"' "\"$p/ctl/**\""
    rule server-alive '"liveliness_token"' "\"$p/alive/server\""
    rule server-observe '"put"' "\"$p/obs/*\""
    rule server-act '"declare_subscriber"' "\"$p/act/*\""
    rule server-control '"declare_queryable", "reply"' "\"$p/ctl/server\""
    local name i
    for name in "${names[@]}"; do
        [[ $name == agent-* ]] || continue
        i=${name#agent-}
        rule "agent-$i-alive" '"liveliness_token"' "\"$p/alive/agent/$i\""
        rule "agent-$i-send" '"put"' "\"$p/act/$i\", \"$p/share/*\""
        rule "agent-$i-receive" '"declare_subscriber"' "\"$p/obs/$i\", \"$p/share/$i\""
        rule "agent-$i-ask" '"query"' "\"$p/advice/*\""
        rule "agent-$i-answer" '"declare_queryable", "reply"' "\"$p/advice/$i\", \"$p/ctl/agent/$i\""
    done
    echo '    ],'
    echo '    subjects: ['
    for name in "${names[@]}"; do
        printf '      { id: "%s", cert_common_names: ["%s"] },\n' "$name" "$name"
    done
    echo '    ],'
    echo '    policies: ['
    for name in "${names[@]}"; do
        printf '      { rules: ["egress", %s], subjects: ["%s"] },\n' "$(rules_of "$name")" "$name"
    done
    echo '    ],'
    echo '  },'
}

for spec in "$@"; do
    name=${spec%%=*}
    address=${spec#*=}
    dir=$out/$name
    mkdir -p "$dir"
    cp "$out/ca.pem" "$dir/ca.pem"
    if [[ $address =~ ^[0-9.]+$ || $address == *:* ]]; then san="IP:$address"; else san="DNS:$address"; fi
    openssl req -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -subj "/CN=$name" \
        -keyout "$dir/key.pem" -out "$dir/req.pem" 2>/dev/null
    openssl x509 -req -in "$dir/req.pem" -CA "$out/ca.pem" -CAkey "$out/ca.key" -CAcreateserial \
        -days "$days" -out "$dir/cert.pem" -extfile <(printf '%s\n' \
            "basicConstraints=critical,CA:FALSE" \
            "keyUsage=critical,digitalSignature" \
            "extendedKeyUsage=serverAuth,clientAuth" \
            "subjectAltName=$san") 2>/dev/null
    rm "$dir/req.pem"
    {
        echo '{'
        echo '  transport: { link: { tls: {'
        printf '    root_ca_certificate: "%s",\n' "$prefix/$name/ca.pem"
        printf '    listen_certificate: "%s", listen_private_key: "%s",\n' "$prefix/$name/cert.pem" "$prefix/$name/key.pem"
        printf '    connect_certificate: "%s", connect_private_key: "%s",\n' "$prefix/$name/cert.pem" "$prefix/$name/key.pem"
        echo '    enable_mtls: true,'
        echo '  } } },'
        acl
        echo '}'
    } >"$dir/zenoh.json5"
    chmod 644 "$dir/ca.pem" "$dir/cert.pem" "$dir/zenoh.json5"
    echo "$dir: $name, $san"
done
