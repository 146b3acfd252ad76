#!/usr/bin/env bash
# Derives the Debian packages of the libraries that mpgc's executables link directly (readelf
# NEEDED -> ldd's path -> dpkg -S), minus what the debootstrap minbase already has, and compares them
# with the library entries of runtime-packages.txt. Exit 1 when a package is missing from the file.
# Usage: deploy/container/derive-packages.sh [BIN_DIR]   (default: <repo>/build/bin)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
BIN="${1:-$HERE/../../build/bin}"
MINBASE="libc6 libgcc-s1"   # in every debootstrap --variant=minbase
derived="$(
  for f in "$BIN"/mpgc_*; do
    [ -x "$f" ] || continue
    ldd "$f" >"${TMPDIR:-/tmp}/derive-ldd.$$" 2>/dev/null || continue
    readelf -d "$f" | awk -F'[][]' '/NEEDED/ { print $2 }' | while read -r lib; do
      path="$(awk -v l="$lib" '$1 == l && $3 ~ /^\// { print $3; exit }' "${TMPDIR:-/tmp}/derive-ldd.$$")"
      [ -n "$path" ] || { echo "?not-found:$lib(${f##*/})"; continue; }
      # usrmerge: dpkg may know the file under /lib or /usr/lib, by its link name or its target
      real="$(readlink -f "$path")"
      pkg=""
      for p in "$path" "$real" "${real#/usr}" "/usr${path#/usr}"; do
        pkg="$(dpkg -S "$p" 2>/dev/null | head -n1 | cut -d: -f1)" && [ -n "$pkg" ] && break
      done
      echo "${pkg:-?no-package:$path}"
    done
  done | sort -u | grep -vxF -f <(tr ' ' '\n' <<<"$MINBASE")
)"
rm -f "${TMPDIR:-/tmp}/derive-ldd.$$"
listed="$(sed -e 's/#.*//' "$HERE/runtime-packages.txt" | tr -s ' \t' '\n\n' | grep -v '^$' | sort -u)"
echo "# libraries' packages derived from $BIN/mpgc_*:"
echo "$derived"
missing="$(comm -23 <(echo "$derived") <(echo "$listed"))"
extra="$(comm -13 <(echo "$derived") <(echo "$listed"))"
[ -z "$extra" ] || { echo "# in runtime-packages.txt but linked by no executable (programs, or stale):"; echo "$extra"; }
if [ -n "$missing" ]; then
  echo "# MISSING from runtime-packages.txt:"; echo "$missing"; exit 1
fi
echo "# runtime-packages.txt covers every library"
