#!/usr/bin/env python3
# Issue 20's closed-loop figures from suite runs: python3 tools/speed_figures.py OUT_DIR...
# (each an mpgc_run --out folder, one sub-folder per scenario with metrics.json). Per scenario:
# sim_s / wall_s, planning p95, and each process's CPU seconds (with its share of the CPU of the
# run) and peak RSS, from metrics.json's "components" (the launcher's account); then the medians.
import glob, json, os, statistics, sys

rows = []
for d in sys.argv[1:]:
    for m in sorted(glob.glob(os.path.join(d, '*', 'metrics.json'))):
        j = json.load(open(m))
        if not j.get('wall_s') or not j.get('sim_s'):
            continue
        rows.append(j)
if not rows:
    sys.exit("no metrics.json with wall_s and sim_s under " + " ".join(sys.argv[1:]))
names = []
for j in rows:
    for n in j.get('components', {}):
        if n not in names:
            names.append(n)
short = {n: n.replace('situational_awareness', 'SA').replace('obstacle_manager', 'OM').replace(
    'guidance_control', 'G&C').replace('ship_simulator', 'sim').replace('scenario_runner', 'runner') for n in names}
print(f"{'scenario':34s} {'sim/wall':>8s} {'wall s':>7s} {'plan p95':>8s}  " +
      " ".join(f"{short[n] + ' cpu s':>12s}" for n in names))
for j in rows:
    c = j.get('components', {})
    total = sum(v['cpu_s'] for v in c.values() if v['cpu_s'] is not None) or float('nan')
    cells = []
    for n in names:
        v = c.get(n)
        cells.append(f"{v['cpu_s']:6.1f} ({100 * v['cpu_s'] / total:3.0f}%)" if v and v['cpu_s'] is not None else f"{'-':>12s}")
    p95 = (j.get('planning_ms') or {}).get('p95')
    print(f"{j['scenario'][:34]:34s} {j['sim_s'] / j['wall_s']:8.1f} {j['wall_s']:7.1f} {p95 if p95 is not None else float('nan'):8.1f}  " + " ".join(cells))
ratio = [j['sim_s'] / j['wall_s'] for j in rows]
print(f"\nsim_s / wall_s over {len(rows)} runs: median {statistics.median(ratio):.1f}, min {min(ratio):.1f}, max {max(ratio):.1f}")
for n in names:
    rss = [j['components'][n]['peak_rss_mb'] for j in rows if n in j.get('components', {})]
    if rss:
        print(f"peak RSS {n}: median {statistics.median(rss):.1f} MB, max {max(rss):.1f} MB")
