#!/usr/bin/env bash
# measure-cost.sh BIN_DIR [RUNS] — the cost of DDS Security on loopback, unsecured vs secured
# (a manual measurement, not a ctest; results go in the report / notes):
#   join     a reader (mpgc_test_intruder, identity ship_simulator) joins a running 1 kHz writer of
#            control/actuators (identity guidance_control): participant creation and time from the
#            reader's start to its first sample
#   start    mpgc_ship_simulator and a reader of nav/own_state (identity guidance_control) started
#            together: time to the reader's first sample (nav at 10 Hz: +0..100 ms of its own)
#   latency  ddsperf ping/pong, size 12 and 1k, round trip (mean, median, 90 %, 99 %)
#   rate     ddsperf pub size 1k at full rate -> sub, kS/s
# ddsperf uses partitions and its own topics, so it runs with a permissions document granting
# topic * in partition * (pitfall 6), signed by the same CA; mpgc's own grants are untouched.
set -euo pipefail
bin="${1:?usage: measure-cost.sh BIN_DIR [RUNS]}"
runs="${2:-5}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)"
repo="$(cd "$here/../.." && pwd -P)"
loop="$repo/deploy/cyclonedds/loopback.xml"
domain="${MPGC_MEASURE_DOMAIN:-229}"
work="$(mktemp -d /tmp/mpgc-measure.XXXXXX)"
trap 'rm -rf "$work"' EXIT
"$repo/deploy/security/make-pki.sh" "$work/pki" >/dev/null
pki="$work/pki"

cat >"$work/perf.xml" <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<dds><permissions><grant name="perf"><subject_name>CN=guidance_control,O=mpgc,C=NO</subject_name>
<validity><not_before>2024-01-01T00:00:00Z</not_before><not_after>2036-01-01T00:00:00Z</not_after></validity>
<allow_rule><domains><id_range><min>0</min><max>230</max></id_range></domains>
<publish><topics><topic>*</topic></topics><partitions><partition>*</partition></partitions></publish>
<subscribe><topics><topic>*</topic></topics><partitions><partition>*</partition></partitions></subscribe>
</allow_rule><default>DENY</default></grant></permissions></dds>
EOF
openssl smime -sign -text -in "$work/perf.xml" -out "$work/perf.p7s" -signer "$pki/ca.pem" -inkey "$pki/ca.key"
sed "s#$pki/permissions/\${MPGC_SECURITY_ID:-MPGC_SECURITY_ID-unset}.p7s#$work/perf.p7s#" "$pki/security.xml" >"$work/perf-security.xml"
cat >"$work/world.yaml" <<EOF
origin: {lat_deg: 38.9, lon_deg: -76.4}
own_ship: {model: mmg, data_dir: "$repo/../shared/data/ship_models", heading_deg: 0, speed_kn: 15}
EOF

uri() { [[ "$1" == secured ]] && echo "file://$loop,file://$2" || echo "file://$loop"; }
field() { awk -v k="$1: " 'index($0, k) == 1 { v = substr($0, length(k) + 1); sub(/ .*/, "", v); print v; exit }' "$2"; }
stats() {  # mean min max of the numbers on stdin
  awk '{ s += $1; if (NR == 1 || $1 < lo) lo = $1; if (NR == 1 || $1 > hi) hi = $1 } END { if (NR) printf "%.1f (%.1f..%.1f, n=%d)", s / NR, lo, hi, NR; else printf "-" }'
}

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
for mode in plain secured; do
  : >"$work/join-part.$mode"; : >"$work/join-first.$mode"; : >"$work/start-first.$mode"
  for i in $(seq "$runs"); do
    CYCLONEDDS_URI="$(uri $mode "$pki/security.xml")" MPGC_SECURITY_ID=guidance_control \
      "$bin/mpgc_test_intruder" --domain "$domain" --seconds 6 --publish control/actuators --rate 1000 >"$work/w.out" 2>&1 &
    w=$!
    sleep 1.5
    CYCLONEDDS_URI="$(uri $mode "$pki/security.xml")" MPGC_SECURITY_ID=ship_simulator \
      "$bin/mpgc_test_intruder" --domain "$domain" --seconds 4 --subscribe control/actuators --wait-first >"$work/r.out" 2>&1
    field participant_ms "$work/r.out" >>"$work/join-part.$mode"
    field "first control/actuators" "$work/r.out" >>"$work/join-first.$mode"
    wait "$w"
    sleep 0.5

    CYCLONEDDS_URI="$(uri $mode "$pki/security.xml")" MPGC_SECURITY_ID=ship_simulator \
      "$bin/mpgc_ship_simulator" --domain "$domain" --log-level warn --set world.file="$work/world.yaml" >/dev/null 2>&1 &
    s=$!
    CYCLONEDDS_URI="$(uri $mode "$pki/security.xml")" MPGC_SECURITY_ID=guidance_control \
      "$bin/mpgc_test_intruder" --domain "$domain" --seconds 5 --subscribe nav/own_state --wait-first >"$work/r.out" 2>&1
    field "first nav/own_state" "$work/r.out" >>"$work/start-first.$mode"
    kill "$s"; wait "$s" || true
    sleep 0.5
  done
  echo "$mode join: participant $(stats <"$work/join-part.$mode") ms, first sample $(stats <"$work/join-first.$mode") ms"
  echo "$mode start: first nav/own_state $(stats <"$work/start-first.$mode") ms"
done

for mode in plain secured; do
  export MPGC_SECURITY_ID=guidance_control
  for size in 12 1k; do
    : >"$work/lat"
    for i in $(seq "$runs"); do
      CYCLONEDDS_URI="$(uri $mode "$work/perf-security.xml")" timeout 20 ddsperf -i "$domain" -D 7 pong >/dev/null 2>&1 &
      p=$!
      CYCLONEDDS_URI="$(uri $mode "$work/perf-security.xml")" timeout 20 ddsperf -i "$domain" -D 6 ping size "$size" >"$work/ping.out" 2>&1
      wait "$p" || true
      # the last report line: mean, median, 90 %, 99 % round trip [us]
      grep ' mean ' "$work/ping.out" | tail -1 | sed -n 's/.*mean \([0-9.]*\)us .*50% \([0-9.]*\)us 90% \([0-9.]*\)us 99% \([0-9.]*\)us.*cnt \([0-9]*\).*/\1 \2 \3 \4 \5/p' >>"$work/lat"
      sleep 0.5
    done
    echo "$mode latency size $size [us] mean $(awk '{print $1}' "$work/lat" | stats), median $(awk '{print $2}' "$work/lat" | stats), 90% $(awk '{print $3}' "$work/lat" | stats), 99% $(awk '{print $4}' "$work/lat" | stats)"
  done
  : >"$work/rate"
  for i in $(seq "$runs"); do
    CYCLONEDDS_URI="$(uri $mode "$work/perf-security.xml")" timeout 20 ddsperf -i "$domain" -D 7 sub >"$work/sub.out" 2>&1 &
    p=$!
    sleep 0.5
    CYCLONEDDS_URI="$(uri $mode "$work/perf-security.xml")" timeout 20 ddsperf -i "$domain" -D 6 pub size 1k >/dev/null 2>&1
    wait "$p" || true
    # mean of the per-second rates from the 2nd second on
    awk '/ size 1024 total / && $2 >= 2.0 { for (i = 1; i <= NF; i++) if ($i == "rate") { s += $(i + 1); n++ } } END { if (n) printf "%.1f\n", s / n }' "$work/sub.out" >>"$work/rate"
    sleep 0.5
  done
  echo "$mode throughput pub size 1k: $(stats <"$work/rate") kS/s"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
