#!/usr/bin/env python3
# Rule-8 and speed figures of suite runs (issue 17 closing notes): python3 tools/rule8_figures.py OUT_DIR...
# where each OUT_DIR is an mpgc_run --out folder (one sub-folder per scenario with metrics.json, components.log).
import json, glob, os, re, statistics, sys
dirs = sys.argv[1:]
alts = []; app = 0; n = 0; ratios = []; speed_runs = 0; speed_plans = 0; emerg = 0; runs = 0; hold_runs = 0
passed = 0; fails = {}
for d in dirs:
    for m in sorted(glob.glob(os.path.join(d, '*', 'metrics.json'))):
        runs += 1
        j = json.load(open(m))
        passed += j['passed']
        if not j['passed']: fails[j['scenario']] = j['failures']
        ds = j['safety_distance_m']
        for e in j['encounters']:
            if e['situation'] in ('head-on', 'crossing-give-way', 'overtaking'):
                n += 1
                a = max(e['max_starboard_change_deg'], e['max_port_change_deg'])
                alts.append(a)
                if e['verdicts'].get('readily_apparent') == 'pass': app += 1
                if e['cpa_m'] is not None: ratios.append(e['cpa_m'] / ds)
        log = os.path.join(os.path.dirname(m), 'components.log')
        if os.path.exists(log):
            t = open(log, errors='replace').read()
            # The planner's own lines only: guidance_control logs every plan it takes with the same reason.
            k = len(re.findall(r'^\[opp\].* info plan \d+ .*speed reduced to', t, re.M))
            speed_plans += k; speed_runs += k > 0
            emerg += len(re.findall(r'^\[opp\].* info plan \d+ .*emergency \(rule 17', t, re.M))
            hold_runs += 'stand-on (rule 17(a))' in t
print(f"runs {runs}, passed {passed}")
if alts:
    print(f"give-way/head-on/overtaking encounters {n}: median alteration {statistics.median(alts):.1f} deg, readily apparent {app}/{n}, median CPA/d_safety {statistics.median(ratios):.2f}")
print(f"plans at reduced speed: {speed_plans} in {speed_runs} runs; emergency plans: {emerg}; runs with a stand-on hold: {hold_runs}")
for k, v in fails.items(): print("FAIL", k, "|", " / ".join(v)[:400])
