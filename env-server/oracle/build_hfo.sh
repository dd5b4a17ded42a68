#!/usr/bin/env bash
# Builds the real HFO headless (the oracle of docs/calibration.md) from its
# public sources, at the commits the calibration used, into a directory
# outside the repository, with a Python environment for its agents:
#
#   env-server/oracle/build_hfo.sh DEST
#   python3 env-server/oracle/hfo_oracle.py --hfo-dir DEST --python DEST/venv/bin/python ...
#
# Sources come from GitHub unless given (a clone, a bare mirror or any URL
# git can read, for machines that cannot reach GitHub):
#
#   HFO_GIT=... RCSSSERVER_GIT=... LIBRCSC_GIT=... env-server/oracle/build_hfo.sh DEST
#
# HFO's CMake fetches rcssserver and librcsc at configure time; this script
# unpacks them into DEST/ext and points the CMake there instead. Debian's
# build packages are installed with apt-get when missing (as root), and
# numpy from PyPI into DEST/venv. About 2-15 minutes on two cores.
set -euo pipefail

HFO_COMMIT=b8b2a1d          # LARG/HFO
RCSSSERVER_COMMIT=82212ee   # mhauskn/rcssserver, the fork HFO's CMake expects
LIBRCSC_COMMIT=d222758      # mhauskn/librcsc, likewise
HFO_GIT=${HFO_GIT:-https://github.com/LARG/HFO.git}
RCSSSERVER_GIT=${RCSSSERVER_GIT:-https://github.com/mhauskn/rcssserver.git}
LIBRCSC_GIT=${LIBRCSC_GIT:-https://github.com/mhauskn/librcsc.git}
PACKAGES=(cmake make g++ flex bison libfl-dev zlib1g-dev python3-venv
          libboost-system-dev libboost-filesystem-dev libboost-program-options-dev
          libboost-thread-dev)

die() { echo "build_hfo: $*" >&2; exit 1; }

[ $# -eq 1 ] || die "usage: $0 DEST (a new or empty directory outside the repository)"
dest=$1
if [ -e "$dest" ] && [ -n "$(ls -A "$dest")" ]; then
    die "$dest is not empty; give a new directory"
fi
mkdir -p "$dest"
dest=$(cd "$dest" && pwd)

missing=()
for p in "${PACKAGES[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    [ "$(id -u)" -eq 0 ] || die "missing Debian packages (install them as root): ${missing[*]}"
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}"
fi

# unpack SOURCE COMMIT DIR: the tree of COMMIT of the repository at SOURCE.
unpack() {
    local tmp
    tmp=$(mktemp -d)
    git clone -q --bare "$1" "$tmp/repo" || die "cannot read $1"
    git --git-dir="$tmp/repo" cat-file -e "$2^{commit}" 2>/dev/null || die "$1 has no commit $2"
    mkdir -p "$3"
    git --git-dir="$tmp/repo" archive "$2" | tar -x -C "$3"
    rm -rf "$tmp"
}
echo "build_hfo: sources into $dest"
unpack "$HFO_GIT" "$HFO_COMMIT" "$dest"
unpack "$RCSSSERVER_GIT" "$RCSSSERVER_COMMIT" "$dest/ext/rcssserver"
unpack "$LIBRCSC_GIT" "$LIBRCSC_COMMIT" "$dest/ext/librcsc"

# The two external projects from the local copies, not from GitHub.
for ext in rcssserver librcsc; do
    sed -i \
        -e "/ExternalProject_Add($ext/,/INSTALL_COMMAND/ s|GIT_REPOSITORY .*|SOURCE_DIR \"\${CMAKE_CURRENT_SOURCE_DIR}/ext/$ext\"|" \
        -e "/ExternalProject_Add($ext/,/INSTALL_COMMAND/ s|GIT_TAG .*|DOWNLOAD_COMMAND \"\"|" \
        "$dest/CMakeLists.txt"
done
grep -q 'ext/rcssserver' "$dest/CMakeLists.txt" && grep -q 'ext/librcsc' "$dest/CMakeLists.txt" \
    || die "HFO's CMakeLists.txt did not take the local sources"

echo "build_hfo: compiling (headless, Release)"
mkdir -p "$dest/build"
(cd "$dest/build" \
    && cmake -DCMAKE_BUILD_TYPE=Release -DBUILD_SOCCERWINDOW=False \
        -DINSTALL_ADDITIONAL_TEAMS=False .. >/dev/null \
    && make -j"$(nproc)" \
    && make install >/dev/null)
for f in bin/HFO bin/rcssserver bin/teams/base/sample_player hfo/libhfo_c.so; do
    [ -e "$dest/$f" ] || die "the build did not produce $f"
done

echo "build_hfo: Python environment with numpy in $dest/venv"
python3 -m venv "$dest/venv"
"$dest/venv/bin/pip" install -q numpy

echo "build_hfo: done. Try:"
echo "  python3 env-server/oracle/hfo_oracle.py --hfo-dir $dest --python $dest/venv/bin/python --policy random --episodes 100 --out /tmp/hfo-random.json"
