#!/usr/bin/env bash
# Builds the mpgc runtime container image offline from Debian packages (README.md in this folder):
#   1. base  localhost/mpgc-base:bookworm: debootstrap --variant=minbase from the Debian archive that
#      apt uses on this machine (read from /etc/apt/sources.list*), imported with `podman import`;
#   2. runtime TAG (default localhost/mpgc:bookworm): Containerfile = base + runtime-packages.txt.
# Each image carries a hash of its inputs in a label; an image whose inputs did not change is not
# built again (a second run takes about a second), a changed Containerfile, package list or apt
# source rebuilds it.
#
# Usage: deploy/container/build-image.sh [--tag TAG] [--with-binaries DIR [--bin-tag TAG]]
#                                        [--rebuild] [--rebuild-base] [--quiet]
#   --tag TAG            runtime image name (default localhost/mpgc:bookworm)
#   --with-binaries DIR  also build an image with DIR/mpgc_* copied into /opt/mpgc/bin (on PATH),
#                        FROM the runtime image; always rebuilt (the executables change every build)
#   --bin-tag TAG        its name (default localhost/mpgc:bookworm-bin)
#   --rebuild            rebuild the runtime image even if its inputs are unchanged
#   --rebuild-base       rebuild the base too (debootstrap again), and so the runtime image
#   --quiet              only the step summary
# Needs root, podman, runc, debootstrap, and the Debian archive reachable (no container registry).
# Environment: MPGC_APT_SOURCES (default /etc/apt) to read another apt configuration, TMPDIR for
# the debootstrap root (default /var/tmp).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export CONTAINERS_CONF="$HERE/containers.conf"

SUITE=bookworm
VARIANT=minbase
BASE_TAG="localhost/mpgc-base:$SUITE"   # the Containerfile's FROM
TAG="localhost/mpgc:$SUITE"
BIN_DIR=""
BIN_TAG="localhost/mpgc:$SUITE-bin"
REBUILD=0
REBUILD_BASE=0
QUIET=0
APT_DIR="${MPGC_APT_SOURCES:-/etc/apt}"
# Bump when the base recipe below changes in a way the hashed inputs do not show.
BASE_RECIPE=4

usage() { sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case "$1" in
    --tag) TAG="${2:?--tag needs a value}"; shift 2 ;;
    --with-binaries) BIN_DIR="${2:?--with-binaries needs a directory}"; shift 2 ;;
    --bin-tag) BIN_TAG="${2:?--bin-tag needs a value}"; shift 2 ;;
    --rebuild) REBUILD=1; shift ;;
    --rebuild-base) REBUILD_BASE=1; REBUILD=1; shift ;;
    --quiet) QUIET=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "build-image: unknown argument '$1' (--help)" >&2; exit 2 ;;
  esac
done

say() { echo "[build-image] $*" >&2; }
die() { echo "[build-image] ERROR: $*" >&2; exit 1; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
SUMMARY=()
step() { SUMMARY+=("$(printf '%-22s %s' "$1" "$2")"); say "$1: $2"; }

T_START=$(now)
[ "$(id -u)" -eq 0 ] || die "run as root (podman with runc and cgroupfs, debootstrap)"
for t in podman runc debootstrap flock; do command -v "$t" >/dev/null || die "'$t' is not installed (deploy/install-deps.sh)"; done
[ -z "$BIN_DIR" ] || [ -x "$BIN_DIR/mpgc_launch" ] || die "--with-binaries $BIN_DIR: no mpgc_launch there"

# One build at a time on this machine (tests may start this concurrently).
exec 9>/run/lock/mpgc-build-image.lock
flock 9

label() {  # label IMAGE KEY: the label's value, empty if the image or the label does not exist
  podman image inspect --format "{{ index .Labels \"$2\" }}" "$1" 2>/dev/null | sed 's/^<no value>$//' || true
}

# --- apt's own Debian sources -------------------------------------------------------------------
# Every enabled `deb` entry of sources.list, sources.list.d/*.list (one-line format) and
# sources.list.d/*.sources (deb822), printed as "URI SUITE COMPONENT..." lines, one per suite.
apt_entries() {
  local files=()
  [ -f "$APT_DIR/sources.list" ] && files+=("$APT_DIR/sources.list")
  for f in "$APT_DIR"/sources.list.d/*.list; do [ -f "$f" ] && files+=("$f"); done
  for f in "${files[@]}"; do
    sed -e 's/#.*//' "$f" | awk '
      $1 == "deb" {
        i = 2
        if ($i ~ /^\[/) { while ($i !~ /\]$/ && i < NF) i++; i++ }   # [ options ]
        uri = $i; suite = $(i + 1); comps = ""
        for (j = i + 2; j <= NF; j++) comps = comps " " $j
        if (uri != "" && suite != "") print uri, suite comps
      }'
  done
  for f in "$APT_DIR"/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    awk '
      function flush(   n, u, s, i, j, us, ss) {
        if (types ~ /(^| )deb( |$)/ && tolower(enabled) != "no") {
          n = split(uris, us, " "); split(suites, ss, " ")
          for (i = 1; i <= n; i++) for (j in ss) print us[i], ss[j] " " comps
        }
        types = uris = suites = comps = ""; enabled = "yes"; field = ""
      }
      BEGIN { enabled = "yes" }
      /^[ \t]*#/ { next }
      /^[ \t]*$/ { flush(); next }
      /^[ \t]/ {   # continuation line (a multi-line field; an inline Signed-By key is skipped)
        if (field == "uris") uris = uris " " $0; else if (field == "suites") suites = suites " " $0
        else if (field == "components") comps = comps " " $0
        next
      }
      {
        field = tolower($0); sub(/:.*/, "", field)
        v = $0; sub(/^[^:]*:[ \t]*/, "", v)
        if (field == "types") types = v
        else if (field == "uris") uris = v
        else if (field == "suites") suites = v
        else if (field == "components") comps = v
        else if (field == "enabled") enabled = v
      }
      END { flush() }' "$f"
  done
}

ENTRIES="$(apt_entries | awk '{ $1 = $1; print }' | awk '!seen[$0]++')"
# The archive that serves the suite itself (the debootstrap mirror) ...
MIRROR="$(awk -v s="$SUITE" '$2 == s { print $1; exit }' <<<"$ENTRIES")"
[ -n "$MIRROR" ] || die "no 'deb' entry for suite $SUITE in $APT_DIR/sources.list*: cannot choose a Debian mirror"
# ... and the image's own apt sources: the same entries for SUITE, SUITE-updates and SUITE-security,
# so that `apt-get install` in the Containerfile gets the versions this machine has (and builds with).
IMAGE_SOURCES="$(awk -v s="$SUITE" '$2 == s || $2 == s "-updates" || $2 == s "-security"' <<<"$ENTRIES" |
  awk '{ comps = ""; for (i = 3; i <= NF; i++) comps = comps (i > 3 ? " " : "") $i
         if (comps == "") comps = "main"
         printf "Types: deb\nURIs: %s\nSuites: %s\nComponents: %s\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n\n", $1, $2, comps }')"
say "Debian archive (from $APT_DIR): $MIRROR"

sha() { sha256sum | cut -c1-16; }
BASE_INPUTS="$(printf 'recipe=%s\nsuite=%s\nvariant=%s\nmirror=%s\n%s\n' "$BASE_RECIPE" "$SUITE" "$VARIANT" "$MIRROR" "$IMAGE_SOURCES" | sha)"

# --- 1. base image --------------------------------------------------------------------------------
ROOTFS=""
cleanup_rootfs() {
  [ -n "$ROOTFS" ] && [ -d "$ROOTFS" ] || return 0
  # debootstrap mounts proc and sys inside the target; never delete through a mount
  findmnt -rn -o TARGET | awk -v r="$ROOTFS" 'index($0, r "/") == 1' | sort -r | while read -r m; do umount -l "$m" || true; done
  rm -rf --one-file-system "$ROOTFS"
  ROOTFS=""
}
trap cleanup_rootfs EXIT

have_base="$(label "$BASE_TAG" org.mpgc.base-inputs)"
if [ "$REBUILD_BASE" -eq 0 ] && [ "$have_base" = "$BASE_INPUTS" ]; then
  step "base" "$BASE_TAG up to date (inputs $BASE_INPUTS), skipped"
else
  [ -n "$have_base" ] && say "base $BASE_TAG: inputs changed ($have_base -> $BASE_INPUTS), rebuilding"
  old_base="$(podman image inspect --format '{{.Id}}' "$BASE_TAG" 2>/dev/null || true)"
  ROOTFS="$(mktemp -d "${TMPDIR:-/var/tmp}/mpgc-rootfs.XXXXXX")"
  log="$ROOTFS.debootstrap.log"
  t0=$(now)
  if ! debootstrap --variant="$VARIANT" "$SUITE" "$ROOTFS" "$MIRROR" >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    die "debootstrap failed (log: $log)"
  fi
  [ "$QUIET" -eq 1 ] || tail -n 2 "$log" >&2
  rm -f "$log"
  step "debootstrap" "$(secs "$t0") s, $(du -sm --one-file-system "$ROOTFS" | cut -f1) MB ($VARIANT $SUITE from $MIRROR)"

  t0=$(now)
  # The image's apt sources: the suite, its updates and security from the same archives as the host.
  rm -f "$ROOTFS/etc/apt/sources.list"
  printf '%s\n' "$IMAGE_SOURCES" >"$ROOTFS/etc/apt/sources.list.d/debian.sources"
  # No daemons are started by package scripts in an image (gpsd's postinst would try).
  printf '#!/bin/sh\nexit 101\n' >"$ROOTFS/usr/sbin/policy-rc.d"
  chmod 755 "$ROOTFS/usr/sbin/policy-rc.d"
  # Keep documentation, manual pages and translations out of every later install (copyrights stay).
  cat >"$ROOTFS/etc/dpkg/dpkg.cfg.d/01-mpgc-nodoc" <<'EOF'
path-exclude /usr/share/doc/*
path-include /usr/share/doc/*/copyright
path-exclude /usr/share/man/*
path-exclude /usr/share/info/*
path-exclude /usr/share/locale/*
path-include /usr/share/locale/locale.alias
path-exclude /usr/share/lintian/*
EOF
  # ... and out of the base itself (what debootstrap installed before that rule): about 45 MB
  find "$ROOTFS/usr/share/doc" -mindepth 1 ! -type d ! -name copyright -delete
  find "$ROOTFS/usr/share/locale" -mindepth 1 -maxdepth 1 ! -name locale.alias -exec rm -rf {} +
  rm -rf "$ROOTFS"/usr/share/man/* "$ROOTFS"/usr/share/info/* "$ROOTFS"/usr/share/lintian/*
  echo 'APT::Install-Recommends "false"; APT::Install-Suggests "false";' >"$ROOTFS/etc/apt/apt.conf.d/01-mpgc-norecommends"
  rm -rf "$ROOTFS"/var/lib/apt/lists/* "$ROOTFS"/var/cache/apt/archives/*.deb "$ROOTFS"/var/cache/apt/*.bin \
         "$ROOTFS"/var/log/apt/* "$ROOTFS"/var/log/dpkg.log "$ROOTFS"/var/log/bootstrap.log
  size_mb="$(du -sm --one-file-system "$ROOTFS" | cut -f1)"
  tar -C "$ROOTFS" --numeric-owner --one-file-system -c . |
    podman import -q --change "LABEL org.mpgc.base-inputs=$BASE_INPUTS" --change "LABEL org.mpgc.role=base" \
      --change 'ENV LANG=C.UTF-8' --change 'CMD ["/bin/bash"]' - "$BASE_TAG" >/dev/null
  step "import" "$(secs "$t0") s (rootfs $size_mb MB after removing apt lists and caches)"
  cleanup_rootfs
  new_base="$(podman image inspect --format '{{.Id}}' "$BASE_TAG")"
  # the previous base, now untagged (fails harmlessly while an image still builds on it)
  [ -n "$old_base" ] && [ "$old_base" != "$new_base" ] && podman rmi "$old_base" >/dev/null 2>&1 || true
fi
BASE_ID="$(podman image inspect --format '{{.Id}}' "$BASE_TAG")"

# --- 2. runtime image -----------------------------------------------------------------------------
INPUTS="$(cat "$HERE/Containerfile" "$HERE/runtime-packages.txt" <(echo "base=$BASE_ID") | sha)"
have="$(label "$TAG" org.mpgc.inputs)"
if [ "$REBUILD" -eq 0 ] && [ "$have" = "$INPUTS" ]; then
  step "build" "$TAG up to date (inputs $INPUTS), skipped"
else
  [ -n "$have" ] && say "$TAG: inputs changed ($have -> $INPUTS), rebuilding"
  old="$(podman image inspect --format '{{.Id}}' "$TAG" 2>/dev/null || true)"
  t0=$(now)
  out="$(mktemp)"
  # --network host: apt inside the build reaches the archive like the host does; the default
  # would create podman's bridge (10.88.0.0/16). --pull=never: the base is local, never a registry.
  if ! podman build --network host --pull=never --layers=false --build-arg "MPGC_INPUTS=$INPUTS" \
         -f "$HERE/Containerfile" -t "$TAG" "$HERE" >"$out" 2>&1; then
    tail -n 40 "$out" >&2
    rm -f "$out"
    die "podman build of $TAG failed"
  fi
  [ "$QUIET" -eq 1 ] || grep -E '^(lib|gpsd|iproute2)[^ ]* [0-9]' "$out" | sed 's/^/[build-image]   /' >&2 || true
  rm -f "$out"
  step "build" "$(secs "$t0") s ($TAG)"
  new="$(podman image inspect --format '{{.Id}}' "$TAG")"
  [ -n "$old" ] && [ "$old" != "$new" ] && podman rmi "$old" >/dev/null 2>&1 || true
fi

# --- optional: an image with the executables ------------------------------------------------------
if [ -n "$BIN_DIR" ]; then
  BIN_DIR="$(cd "$BIN_DIR" && pwd)"
  t0=$(now)
  ctx="$(mktemp -d "${TMPDIR:-/var/tmp}/mpgc-binctx.XXXXXX")"
  mkdir "$ctx/bin"
  cp -l "$BIN_DIR"/mpgc_* "$ctx/bin/" 2>/dev/null || cp "$BIN_DIR"/mpgc_* "$ctx/bin/"
  cat >"$ctx/Containerfile" <<EOF
FROM $TAG
COPY bin/ /opt/mpgc/bin/
ENV PATH=/opt/mpgc/bin:/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
LABEL org.mpgc.role=runtime+binaries org.mpgc.binaries-from=$BIN_DIR
EOF
  old="$(podman image inspect --format '{{.Id}}' "$BIN_TAG" 2>/dev/null || true)"
  if ! podman build --network none --pull=never --layers=false -t "$BIN_TAG" "$ctx" >"$ctx/log" 2>&1; then
    tail -n 20 "$ctx/log" >&2; rm -rf "$ctx"; die "podman build of $BIN_TAG failed"
  fi
  rm -rf "$ctx"
  new="$(podman image inspect --format '{{.Id}}' "$BIN_TAG")"
  [ -n "$old" ] && [ "$old" != "$new" ] && podman rmi "$old" >/dev/null 2>&1 || true
  step "binaries" "$(secs "$t0") s ($BIN_TAG: $BIN_DIR/mpgc_* in /opt/mpgc/bin)"
fi

size() { podman image inspect --format '{{.Size}}' "$1" | awk '{ printf "%.0f MB", $1 / 1e6 }'; }
say "images: $BASE_TAG $(size "$BASE_TAG"), $TAG $(size "$TAG")${BIN_DIR:+, $BIN_TAG $(size "$BIN_TAG")}"
step "total" "$(secs "$T_START") s"
printf '%s\n' "${SUMMARY[@]}" | sed 's/^/[build-image] summary: /' >&2
echo "$TAG"
