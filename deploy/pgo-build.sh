#!/usr/bin/env bash
# Profile-guided release build of `env-server` and `coordinator` (docs/speed.md, "PGO").
#
#   deploy/pgo-build.sh            # -> target/x86_64-unknown-linux-gnu/release/{env-server,coordinator}
#
# 1. builds the two executables with LLVM's instrumentation, 2. runs a random
# rollout and a short in-process AdHocTD run to record where the time goes,
# 3. merges the profiles with the toolchain's own llvm-profdata (rustup's
# llvm-tools component: its LLVM must be rustc's; Debian's llvm-profdata is
# older), 4. rebuilds with the profile. Only the crates the simulator and the
# agents spend their time in get the flags (env_server, agent, coordinator;
# glam's vector methods are inlined into them): the dependencies (zenoh,
# tokio, libm, ...) are compiled once, as in an ordinary release build, and
# shared by both steps. (Not libm: rebuilding it would rebuild everything
# that depends on it, zenoh's crates included.) The builds go to
# target/<host triple>/release, apart from `cargo build --release`'s, so the
# first run compiles the dependencies once more (about 25 minutes on two
# cores); later runs rebuild only the three crates.
#
# PGO changes inlining and code layout, never a floating-point operation:
# the results are bit for bit those of `cargo build --release` (check with
# the fingerprint example and a run's files, docs/speed.md).
#
# Environment: CARGO_TARGET_DIR (default: target), PGO_DIR (profiles,
# default: $CARGO_TARGET_DIR/pgo-profiles).
set -euo pipefail
cd "$(dirname "$0")/.."

HOST=$(rustc -vV | sed -n 's/^host: //p')
TARGET_DIR=${CARGO_TARGET_DIR:-target}
TARGET_DIR=$(mkdir -p "$TARGET_DIR" && cd "$TARGET_DIR" && pwd)
PGO_DIR=${PGO_DIR:-$TARGET_DIR/pgo-profiles}
OUT="$TARGET_DIR/$HOST/release"
SYSROOT=$(rustc --print sysroot)
PROFDATA="$SYSROOT/lib/rustlib/$HOST/bin/llvm-profdata"
if [ ! -x "$PROFDATA" ]; then
    echo "llvm-profdata of this toolchain missing: rustup component add llvm-tools" >&2
    exit 1
fi

# The wrapper adds the PGO flags to the crates named in PGO_CRATES only.
WRAPPER="$TARGET_DIR/pgo-rustc-wrapper.sh"
cat > "$WRAPPER" <<'EOF'
#!/usr/bin/env bash
# Called by cargo as: wrapper rustc args...
rustc=$1; shift
crate=
prev=
for a in "$@"; do
    if [ "$prev" = "--crate-name" ]; then crate=$a; fi
    prev=$a
done
case " $PGO_CRATES " in
    *" $crate "*) exec "$rustc" "$@" $PGO_FLAGS ;;
    *) exec "$rustc" "$@" ;;
esac
EOF
chmod +x "$WRAPPER"
export PGO_CRATES="env_server agent coordinator"
PACKAGES=(-p env-server -p env-server-process -p agent -p coordinator)

build() { # $1: the flags of the PGO crates
    # Cargo does not see the wrapper's flags: the PGO crates are rebuilt by hand.
    cargo clean --release --target "$HOST" "${PACKAGES[@]}" 2>/dev/null || true
    PGO_FLAGS="$1" RUSTC_WRAPPER="$WRAPPER" CARGO_TARGET_DIR="$TARGET_DIR" \
        cargo build --release --target "$HOST" -p env-server-process -p coordinator
}

rm -rf "$PGO_DIR" && mkdir -p "$PGO_DIR"
echo "== instrumented build" >&2
build "-Cprofile-generate=$PGO_DIR"
echo "== training runs" >&2
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
"$OUT/env-server" rollout --policy random --episodes 3000 --json > /dev/null
"$OUT/env-server" rollout --policy uniform --episodes 1000 --json > /dev/null
"$OUT/coordinator" run --algorithm adhoc-td --runs 1 --episodes 1500 --threads 1 \
    --transport in-process --out "$WORK/run" > /dev/null
"$PROFDATA" merge -o "$PGO_DIR/merged.profdata" "$PGO_DIR"/*.profraw
echo "== optimised build" >&2
build "-Cprofile-use=$PGO_DIR/merged.profdata"
echo "PGO build: $OUT/env-server, $OUT/coordinator" >&2
