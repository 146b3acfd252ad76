#!/usr/bin/env python3
# Smoke test of ./mpgc bench chain: runs mpgc_bench_chain with a few samples and checks that its
# last line is JSON with finite, positive latencies (every hop, end to end, ddsperf's one hop, the
# large-sample copy) and that no row lost most of its samples.
import json, math, subprocess, sys

bench = sys.argv[1]
args = sys.argv[2:]
p = subprocess.run([bench] + args, capture_output=True, text=True, timeout=240)
sys.stdout.write(p.stdout)
sys.stderr.write(p.stderr)
if p.returncode != 0:
    sys.exit(f"FAIL: mpgc_bench_chain exited {p.returncode}")
lines = [l for l in p.stdout.splitlines() if l.strip()]
try:
    j = json.loads(lines[-1])
except (IndexError, json.JSONDecodeError) as e:
    sys.exit(f"FAIL: the last line is not JSON: {e}")

bad = []
def positive(what, x):
    if not isinstance(x, (int, float)) or isinstance(x, bool) or not math.isfinite(x) or x <= 0:
        bad.append(f"{what} = {x!r}")

if not j.get("ddsperf"):
    bad.append("no ddsperf result")
else:
    positive("ddsperf one_hop_us_median", j["ddsperf"].get("one_hop_us_median"))
    positive("ddsperf one_hop_us_p99", j["ddsperf"].get("one_hop_us_p99"))
rows = j.get("rows") or []
if not rows:
    bad.append("no rows")
for r in rows:
    n = r.get("name")
    if not r.get("samples") or r.get("lost", 0) > r["samples"]:
        bad.append(f"{n}: {r.get('samples')} samples, {r.get('lost')} lost")
    for k, s in (r.get("hop_ms") or {}).items():
        positive(f"{n} {k} median", s.get("median"))
        positive(f"{n} {k} p99", s.get("p99"))
    if len(r.get("hop_ms") or {}) != 4:
        bad.append(f"{n}: {len(r.get('hop_ms') or {})} hops, not 4")
    for k in ("end_to_end_ms", "planning_ms", "end_to_end_cached_plan_ms"):
        positive(f"{n} {k} median", (r.get(k) or {}).get("median"))
        positive(f"{n} {k} p99", (r.get(k) or {}).get("p99"))
    positive(f"{n} ratio_vs_ddsperf_hops", r.get("ratio_vs_ddsperf_hops"))
    e2e = r["end_to_end_ms"]["median"]
    if isinstance(e2e, (int, float)) and e2e < sum(s["median"] for s in r["hop_ms"].values()) * 0.5:
        bad.append(f"{n}: end to end {e2e} ms shorter than half the sum of the hops' medians")
c = j.get("copy")
if not c:
    bad.append("no copy result")
else:
    for k in ("to_c_ms", "from_c_ms", "write_ms", "write_to_take_ms"):
        positive(f"copy {k} median", (c.get(k) or {}).get("median"))
if bad:
    sys.exit("FAIL:\n  " + "\n  ".join(bad))
print("OK")
