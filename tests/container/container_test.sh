#!/usr/bin/env bash
# Containers on separate "hosts": builds the mpgc runtime image (deploy/container/build-image.sh;
# cached, so a second run only checks the inputs' hash), checks that every mpgc_* executable
# resolves all its libraries inside it, then runs two hosts as podman containers on two network
# namespaces joined by a veth on a subnet that exists only inside them: mpgc_launch with
# mpgc_test_talker on A, mpgc_launch with mpgc_test_listener on B. The listener must receive the
# samples; SIGTERM to `podman run` must stop B's mpgc_launch cleanly (exit code 0), and a failing
# component's exit code must come out of `podman run` (mpgc_launch: 1).
#
# The executables are not in the image: the bin directory is bind-mounted at its own path.
# Environment: MPGC_BIN_DIR (default <repo>/build/bin). Exit 77 = skipped (not root, no podman).
set -uo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
BIN="$(cd "${MPGC_BIN_DIR:-$REPO/build/bin}" 2>/dev/null && pwd -P)" || { echo "FAIL: no bin directory ${MPGC_BIN_DIR:-$REPO/build/bin}"; exit 1; }
IMAGE="${MPGC_CONTAINER_IMAGE:-localhost/mpgc:bookworm}"
export CONTAINERS_CONF="$REPO/deploy/container/containers.conf"

log() { echo "[container_test] $*"; }
fail() { echo "[container_test] FAIL: $*"; exit 1; }
skip() { echo "[container_test] SKIP: $*"; exit 77; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

[ "$(id -u)" -eq 0 ] || skip "needs root (network namespaces, podman with runc and cgroupfs)"
for t in podman runc debootstrap ip; do command -v "$t" >/dev/null || skip "'$t' is not installed (deploy/install-deps.sh)"; done
for e in mpgc_launch mpgc_test_talker mpgc_test_listener mpgc_ship_simulator; do
  [ -x "$BIN/$e" ] || fail "$BIN/$e is missing: build first"
done

ID=$$
A="mpgcCA$ID"; B="mpgcCB$ID"; IA="cta$ID"; IB="ctb$ID"
NET="10.79.$((ID % 250 + 1))"
DOMAIN=$((1 + ID % 200))
WORK="$(mktemp -d /tmp/mpgc-container-test.XXXXXX)"
CA="mpgc-ct-a-$ID"; CB="mpgc-ct-b-$ID"; CX="mpgc-ct-x-$ID"
cleanup() {
  for c in "$CA" "$CB" "$CX"; do podman rm -f -t 0 "$c" >/dev/null 2>&1; done
  ip netns del "$A" 2>/dev/null; ip netns del "$B" 2>/dev/null   # the veth goes with them
  rm -rf "$WORK"
}
trap cleanup EXIT

# --- the image --------------------------------------------------------------------------------------
t0=$(now)
"$REPO/deploy/container/build-image.sh" --tag "$IMAGE" --quiet >"$WORK/build.log" 2>&1 ||
  { cat "$WORK/build.log"; fail "deploy/container/build-image.sh failed (output above)"; }
grep 'summary:' "$WORK/build.log"
log "image $IMAGE ready in $(secs "$t0") s"

# --- every executable resolves its libraries in the image ------------------------------------------
t0=$(now)
out="$(podman run --rm --name "$CX" --network none -v "$BIN:$BIN:ro" "$IMAGE" sh -c '
  n=0; for f in "$1"/mpgc_*; do n=$((n + 1)); ldd "$f" | grep "not found" | sed "s|^|$f: |"; done
  echo "checked $n executables"; "$1"/mpgc_ship_simulator --help >/dev/null && echo "help ok"' sh "$BIN" 2>&1)"
echo "$out" | sed 's/^/  /'
echo "$out" | grep -q 'not found' && fail "libraries missing in $IMAGE: add their packages to deploy/container/runtime-packages.txt"
echo "$out" | grep -q '^help ok$' || fail "mpgc_ship_simulator --help did not run in $IMAGE"
log "libraries and --help checked in $(secs "$t0") s"

# --- two hosts: namespaces A and B, a veth between them ---------------------------------------------
ip netns add "$A" && ip netns add "$B" &&
  ip -n "$A" link add "$IA" type veth peer name "$IB" netns "$B" &&
  ip -n "$A" addr add "$NET.1/24" dev "$IA" && ip -n "$B" addr add "$NET.2/24" dev "$IB" &&
  ip -n "$A" link set lo up && ip -n "$B" link set lo up &&
  ip -n "$A" link set "$IA" up && ip -n "$B" link set "$IB" up || fail "could not create network namespaces (ip netns)"

cyclone() {  # cyclone IFACE: the host's interface, no multicast, both hosts as unicast peers
  cat <<EOF
<CycloneDDS xmlns="https://cdds.io/config"><Domain Id="any"><General><Interfaces><NetworkInterface name="$1"/></Interfaces>
<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>
<MaxAutoParticipantIndex>50</MaxAutoParticipantIndex><Peers><Peer address="$NET.1"/><Peer address="$NET.2"/></Peers>
</Discovery></Domain></CycloneDDS>
EOF
}
cyclone "$IA" >"$WORK/cyclone_A.xml"
cyclone "$IB" >"$WORK/cyclone_B.xml"
cat >"$WORK/A.yaml" <<'EOF'
components:
  - {name: talker, executable: mpgc_test_talker, set: {rate: 20, count: 40}}
EOF
cat >"$WORK/B.yaml" <<'EOF'
components:
  - {name: listener, executable: mpgc_test_listener}
EOF
cat >"$WORK/fail.yaml" <<'EOF'
components:
  - {name: talker, executable: mpgc_test_talker, set: {rate: 20, count: 2, exit_code: 3}}
EOF

host() {  # host NAME NETNS IFACE_CONFIG LAUNCH_FILE: one host of the deployment as a container
  exec podman run --rm --name "$1" --network "ns:/run/netns/$2" -v "$BIN:$BIN:ro" -v "$WORK:$WORK:ro" \
    -e "CYCLONEDDS_URI=file://$3" "$IMAGE" "$BIN/mpgc_launch" "$4" --domain "$DOMAIN"
}

# The container sees its namespace: lo and the veth, nothing of the machine's network.
links="$(podman run --rm --name "$CX" --network "ns:/run/netns/$A" "$IMAGE" ip -br link 2>&1 | awk '{ sub(/@.*/, "", $1); print $1 }' | sort | tr '\n' ' ')"
[ "$links" = "$IA lo " ] || fail "container on $A sees links '$links', expected '$IA lo'"
log "container on $A sees: $links"

t0=$(now)
host "$CB" "$B" "$WORK/cyclone_B.xml" "$WORK/B.yaml" >"$WORK/B.log" 2>&1 &
PB=$!
for _ in $(seq 100); do grep -q 'running on DDS domain' "$WORK/B.log" && break; sleep 0.1; done
timeout 60 bash -c "$(declare -f host); BIN='$BIN' WORK='$WORK' IMAGE='$IMAGE' DOMAIN='$DOMAIN'; host '$CA' '$A' '$WORK/cyclone_A.xml' '$WORK/A.yaml'" >"$WORK/A.log" 2>&1
RA=$?
log "talker host $A: exit code $RA after $(secs "$t0") s"
sed 's/^/  A| /' "$WORK/A.log" | tail -n 4
# the samples crossed the link (the listener may miss the first ones while discovery completes)
for _ in $(seq 100); do grep -q 'received 10 (value' "$WORK/B.log" && break; sleep 0.1; done
t1=$(now)
kill -TERM "$PB"   # podman run proxies it to mpgc_launch, PID 1 in the container
RB=124
for _ in $(seq 150); do kill -0 "$PB" 2>/dev/null || { wait "$PB"; RB=$?; break; }; sleep 0.1; done
log "listener host $B: exit code $RB $(secs "$t1") s after SIGTERM to podman run"
sed 's/^/  B| /' "$WORK/B.log" | grep -v 'info received [0-9]* ' 
echo "  B| ... $(grep -c 'info received [0-9]* (value' "$WORK/B.log") samples received"

[ "$RA" -eq 0 ] || fail "the talker's container exited with code $RA"
grep -q '\[launch\] talker exited with code 0' "$WORK/A.log" || fail "talker did not finish in its container"
grep -q 'received 10 (value' "$WORK/B.log" || fail "samples did not cross the veth link from $A to $B"
[ "$RB" -ne 124 ] || fail "the listener's container did not stop within 15 s of SIGTERM"
grep -q '\[launch\] received Terminated' "$WORK/B.log" || fail "SIGTERM to podman run did not reach mpgc_launch"
grep -q '\[launch\] listener exited with code 0' "$WORK/B.log" || fail "the listener did not stop cleanly"
[ "$RB" -eq 0 ] || fail "podman run of the listener's host exited with $RB, expected 0"

# A failing required component: mpgc_launch exits 1, and so does podman run.
timeout 60 podman run --rm --name "$CX" --network "ns:/run/netns/$A" -v "$BIN:$BIN:ro" -v "$WORK:$WORK:ro" \
  -e "CYCLONEDDS_URI=file://$WORK/cyclone_A.xml" "$IMAGE" "$BIN/mpgc_launch" "$WORK/fail.yaml" --domain "$DOMAIN" >"$WORK/fail.log" 2>&1
RF=$?
[ "$RF" -eq 1 ] || { cat "$WORK/fail.log"; fail "podman run with a failing component exited with $RF, expected mpgc_launch's 1"; }
log "failing component: podman run exited with mpgc_launch's code 1"
log "PASS"
