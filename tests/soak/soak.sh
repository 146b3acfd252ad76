#!/usr/bin/env bash
# Soak test (issue 15 item 7): sail one scenario closed-loop in lockstep with mpgc_run and sample
# the memory of every process of the run, then judge whether any of them grew after start-up.
#
#   tests/soak/soak.sh [--out DIR] [--period S] [--mark F] [--max-growth-mib M] [--max-growth-pct P]
#                      SCENARIO [-- MPGC_RUN_ARGS...]
#   tests/soak/soak.sh --report OUT/<scenario> [--mark F] [--max-growth-mib M] [--max-growth-pct P]
#                      (no run: the table and verdict again from that run's rss.csv)
#
# Every --period wall seconds (5) it reads VmRSS, VmHWM and RssAnon from /proc/<pid>/status of
# mpgc_run and of each of its descendants that is an mpgc_* executable (mpgc_launch and the five
# components it starts), with the run's simulated time (the last "sim N s" progress line of
# mpgc_run), into OUT/<scenario>/rss.csv; mpgc_run's output goes to OUT/<scenario>/soak_run.log.
# At the end it prints, per process: RSS at the start-up mark (the first sample at --mark of the
# run's simulated time, 10 %), RSS at the end (the last sample while the components were still
# running, i.e. before mpgc_run's evaluation), the peak (VmHWM), and the growth mark -> end.
#
# THRESHOLD (fixed before the run; tests/soak/README.md): a process FAILS when it grew from the
# mark to the end by more than --max-growth-mib (5 MiB) AND by more than --max-growth-pct (10 %)
# of its RSS at the mark.
#  * Why 5 MiB: after start-up the components hold 10-40 MiB. What may move without being a leak:
#    glibc's arenas and free lists (a plan's tree and k-nearest grid are allocated and freed every
#    15 s and need not land at the same addresses), Cyclone DDS's receive and history buffers, code
#    and data pages touched late (RSS counts file-backed pages too) - together a few MiB at most.
#    What 5 MiB still catches over the 90 % of a 24 h run after the mark (777 600 steps of 0.1 s,
#    about 5 200 plans, about 100 000 AIS reports of 13 targets): 8 bytes per step, 1 kB per plan,
#    50 bytes per AIS report.
#  * Why also 10 %: the AND keeps a process of several hundred MiB (a chart of 10^6 points in
#    obstacle_manager) from failing on allocator noise that scales with its size; for the processes
#    of this soak (all < 50 MiB) the 5 MiB bound is the binding one.
#  * mpgc_run is the recorder and evaluator, not part of the ship: it keeps the whole run in memory
#    by design (sim/truth of every ship every simulated second, guidance/status at 2 Hz, every
#    plan) to evaluate it at the end. Its allowance is that record on top of the threshold:
#    B = 8 + 40 (1 + N) + 2 x 24 + 70 bytes per simulated second (a time stamp, a 40-byte state of
#    each of the own ship and N targets, two 24-byte guidance records, a ~1 kB plan record every
#    15 s; components/scenario_runner evaluation.hpp), times 2: the vectors grow by doubling and
#    the buffers they leave behind, together as large as the current one, may stay in the heap.
#    N is read from the run's timeseries.csv (or world.yaml).
#
# Exit: 0 no process grew beyond the threshold (whatever the scenario's own pass criteria said:
# they are printed); 1 a process grew beyond it; 2 usage; 3 the soak could not judge: the run
# aborted before its end, a component was restarted (its RSS started again), or too few samples.
#
# Environment: MPGC_BIN_DIR (default <repo>/build/bin), and as ./mpgc sets them CYCLONEDDS_URI
# (loopback), MPGC_SHARED_DATA (<repo>/../shared/data), MPGC_SOURCE_DIR (<repo>).
# One run at a time: the 2 cores are shared, and a lockstep run's speed is what it measures too.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BIN="${MPGC_BIN_DIR:-$REPO/build/bin}"
export CYCLONEDDS_URI="${CYCLONEDDS_URI:-file://$REPO/deploy/cyclonedds/loopback.xml}"
export MPGC_SHARED_DATA="${MPGC_SHARED_DATA:-$REPO/../shared/data}"
export MPGC_SOURCE_DIR="$REPO"

OUT="$REPO/out/soak"
PERIOD=5
MARK=0.10
MAX_MIB=5
MAX_PCT=10
SCENARIO=""
REPORT=""
RUN_ARGS=()

usage() { sed -n '2,14p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --out) OUT="$2"; shift 2 ;;
    --period) PERIOD="$2"; shift 2 ;;
    --mark) MARK="$2"; shift 2 ;;
    --max-growth-mib) MAX_MIB="$2"; shift 2 ;;
    --max-growth-pct) MAX_PCT="$2"; shift 2 ;;
    --report) REPORT="$2"; shift 2 ;;
    -h | --help) usage ;;
    --) shift; RUN_ARGS=("$@"); break ;;
    -*) echo "soak.sh: unknown option $1" >&2; usage ;;
    *) [ -z "$SCENARIO" ] || { echo "soak.sh: one scenario at a time" >&2; exit 2; }; SCENARIO="$1"; shift ;;
  esac
done
if [ -n "$REPORT" ]; then
  [ -f "$REPORT/rss.csv" ] || { echo "soak.sh: no $REPORT/rss.csv" >&2; exit 2; }
  DIR="$(cd "$REPORT" && pwd)"
  NAME="$(basename "$DIR")"
  CSV="$DIR/rss.csv"
  LOG="$DIR/soak_run.log"
else
[ -n "$SCENARIO" ] || usage
[ -f "$SCENARIO" ] || { echo "soak.sh: no scenario file $SCENARIO" >&2; exit 2; }
[ -x "$BIN/mpgc_run" ] || { echo "soak.sh: $BIN/mpgc_run is not built" >&2; exit 2; }
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"

LOG="$OUT/soak_run.$$.log"
"$BIN/mpgc_run" "$SCENARIO" --out "$OUT" "${RUN_ARGS[@]}" >"$LOG" 2>&1 &
RUN_PID=$!
# Interrupted: stop the run (mpgc_run stops its launcher and so the components on SIGINT).
cleanup() {
  if kill -0 "$RUN_PID" 2>/dev/null; then
    kill -INT "$RUN_PID" 2>/dev/null || true
  fi
}
trap 'cleanup; exit 130' INT TERM
T0=$EPOCHREALTIME

# The scenario's name (and so its output folder) from mpgc_run's first line.
NAME=""
for _ in $(seq 1 600); do
  NAME="$(sed -n 's/^running \([^ ]*\) (.*/\1/p' "$LOG" | head -n 1)"
  [ -n "$NAME" ] && break
  kill -0 "$RUN_PID" 2>/dev/null || break
  sleep 0.1
done
if [ -z "$NAME" ]; then
  echo "soak.sh: mpgc_run did not start the scenario:" >&2
  cat "$LOG" >&2
  wait "$RUN_PID" || true
  exit 3
fi
DIR="$OUT/$NAME"
mkdir -p "$DIR"
CSV="$DIR/rss.csv"
echo "sample,wall_s,sim_s,process,pid,vmrss_kib,vmhwm_kib,rssanon_kib" >"$CSV"
echo "soak: $NAME ($SCENARIO), mpgc_run pid $RUN_PID, sampling every $PERIOD s into $CSV"

# Descendants of a pid, from the ppid field of /proc/*/stat.
descendants() {
  local -A kids=()
  local st line rest pid ppid
  for st in /proc/[0-9]*/stat; do
    { read -r line <"$st"; } 2>/dev/null || continue   # a process may end between glob and read
    pid="${line%% *}"
    rest="${line##*) }"   # after the command name, which may hold spaces and parentheses
    read -r _ ppid _ <<<"$rest"
    kids[$ppid]+="$pid "
  done
  local queue=("$1") out=() p c
  while [ ${#queue[@]} -gt 0 ]; do
    p="${queue[0]}"
    queue=("${queue[@]:1}")
    for c in ${kids[$p]:-}; do out+=("$c"); queue+=("$c"); done
  done
  echo "${out[@]:-}"
}

sim_now() {
  tail -n 40 "$LOG" 2>/dev/null | grep -oE ' sim +[0-9]+ s ' | tail -n 1 | grep -oE '[0-9]+' || echo ""
}

N=0
while kill -0 "$RUN_PID" 2>/dev/null; do
  N=$((N + 1))
  wall=$(awk -v a="$EPOCHREALTIME" -v b="$T0" 'BEGIN {print a - b}')
  sim="$(sim_now)"
  for p in "$RUN_PID" $(descendants "$RUN_PID"); do
    exe="$(readlink "/proc/$p/exe" 2>/dev/null)" || continue
    name="$(basename "${exe% (deleted)}")"   # " (deleted)": the binary was rebuilt during the run
    case "$name" in mpgc_*) ;; *) continue ;; esac
    read -r rss hwm anon < <(awk '/^VmRSS:/ {r=$2} /^VmHWM:/ {h=$2} /^RssAnon:/ {a=$2}
                                  END {print r+0, h+0, a+0}' "/proc/$p/status" 2>/dev/null || echo "0 0 0")
    [ "$rss" -gt 0 ] || continue
    printf '%d,%.1f,%s,%s,%d,%d,%d,%d\n' "$N" "$wall" "${sim:-}" "$name" "$p" "$rss" "$hwm" "$anon" >>"$CSV"
  done
  sleep "$PERIOD"
done
set +e
wait "$RUN_PID"
RC=$?
set -e
trap - INT TERM
mv "$LOG" "$DIR/soak_run.log"
LOG="$DIR/soak_run.log"
WALL=$(awk -v a="$EPOCHREALTIME" -v b="$T0" 'BEGIN {print a - b}')
fi

echo
grep -E '^(scenario|'"$NAME"' |    why|[0-9]+ passed)' "$LOG" 2>/dev/null || tail -n 5 "$LOG" 2>/dev/null || true
if [ -z "$REPORT" ]; then
  printf 'soak: mpgc_run exit code %d, wall %.0f s, %d samples\n' "$RC" "$WALL" "$N"
fi
echo "soak: end of the run: $(cat "$DIR/end.txt" 2>/dev/null || echo 'no end.txt (the run did not finish)')"

# Ships of the run for mpgc_run's record allowance: the targets of timeseries.csv, else world.yaml.
TARGETS=""
if [ -f "$DIR/timeseries.csv" ]; then
  TARGETS=$(head -n 1 "$DIR/timeseries.csv" | tr ',' '\n' | grep -cE '^tgt[0-9]+_x_m$' || true)
fi
if [ -z "$TARGETS" ] || [ "$TARGETS" = 0 ]; then
  TARGETS=$(grep -cE '^ *- *\{?mmsi:|^ *mmsi:' "$DIR/world.yaml" 2>/dev/null || echo 0)
fi

set +e
awk -F, -v mark="$MARK" -v max_mib="$MAX_MIB" -v max_pct="$MAX_PCT" -v targets="$TARGETS" '
  NR == 1 { next }
  {
    s = $1; sim[s] = ($3 == "" ? -1 : $3 + 0); name = $4
    sub(/ \(deleted\)$/, "", name)   # rss.csv of a run whose binaries were rebuilt meanwhile
    if (!(name in seen)) { seen[name] = 1; order[++np] = name }
    key = s SUBSEP name
    if (!(key in rss) || $6 > rss[key]) rss[key] = $6
    if ($7 > peak[name]) peak[name] = $7
    pids[name, $5] = 1
    if (name == "mpgc_launch") last_launch = s
    if (s > last) last = s
    if (sim[s] > simmax) simmax = sim[s]
  }
  END {
    if (last_launch == 0 || simmax <= 0) { print "soak: no samples while the components ran"; exit 3 }
    for (s = 1; s <= last; s++) if ((s in sim) && sim[s] >= mark * simmax) { m = s; break }
    if (m == 0 || m >= last_launch) { print "soak: too few samples after the mark"; exit 3 }
    bytes_per_s = 8 + 40 * (1 + targets) + 2 * 24 + 70
    printf "\nstart-up mark: sample %d at sim %d s (%.0f %% of %d s); end: sample %d at sim %d s (last with the components running)\n",
           m, sim[m], 100 * mark, simmax, last_launch, sim[last_launch]
    printf "threshold: grew > %s MiB and > %s %% from the mark to the end (mpgc_run: beyond its record of the run, 2 x %d B per sim s, %d targets)\n\n",
           max_mib, max_pct, bytes_per_s, targets
    printf "| process | pids | RSS at mark [MiB] | RSS at end [MiB] | peak VmHWM [MiB] | growth [MiB] | growth [%%] | allowed [MiB] | verdict |\n"
    printf "|---|---|---|---|---|---|---|---|---|\n"
    bad = 0; restarted = 0
    for (i = 1; i <= np; i++) {
      n = order[i]
      np_ = 0; for (k in pids) { split(k, a, SUBSEP); if (a[1] == n) np_++ }
      a0 = rss[m, n]
      e = -1; for (s = last_launch; s >= m; s--) if (((s, n) in rss)) { e = rss[s, n]; es = s; break }
      if (a0 == "" || e < 0) { printf "| %s | %d | - | - | %.1f | - | - | - | not sampled at both marks |\n", n, np_, peak[n] / 1024; restarted = 1; continue }
      g = (e - a0) / 1024; pct = 100 * (e - a0) / a0
      allow = max_mib
      if (n == "mpgc_run") allow += 2 * bytes_per_s * (sim[es] - sim[m]) / 1048576
      excess = g - (allow - max_mib)
      fail = excess > max_mib && 100 * excess * 1024 / a0 > max_pct
      v = fail ? "GREW" : "ok"
      if (np_ > 1) { v = v " (restarted: " np_ " pids)"; restarted = 1 }
      if (fail) bad = 1
      printf "| %s | %d | %.1f | %.1f | %.1f | %+.2f | %+.1f | %.1f | %s |\n", n, np_, a0 / 1024, e / 1024, peak[n] / 1024, g, pct, allow, v
    }
    if (np < 7) { printf "\nsoak: only %d mpgc processes were sampled (7 expected)\n", np; restarted = 1 }
    if (bad) { print "\nsoak: FAIL: a process grew beyond the threshold"; exit 1 }
    if (restarted) { print "\nsoak: CANNOT JUDGE: a process was restarted or missing"; exit 3 }
    print "\nsoak: PASS: no process grew beyond the threshold after start-up"
    exit 0
  }' "$CSV" | tee "$DIR/rss_summary.md"
VERDICT=${PIPESTATUS[0]}
set -e
if [ "$VERDICT" = 0 ] && [ ! -f "$DIR/end.txt" ]; then
  echo "soak: CANNOT JUDGE: the run did not reach its end (see $DIR/components.log)"
  VERDICT=3
fi
exit "$VERDICT"
