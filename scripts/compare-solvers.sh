#!/usr/bin/env bash
# Runs each scene with both solvers back to back (dynamic = the paper's explicit relaxation, newton =
# the quasi-static solver with its active window) and writes OUT/agreement.md and OUT/agreement.csv:
# pattern, first sideways snap, wavelength, amplitude, skew, and the CPU time of each run; and
# OUT/theta_tip.png, the theta_tip histories of both solvers overlaid.
# Usage: scripts/compare-solvers.sh OUT_DIR [SCENE...]   (default: fig2b, fig2a alpha 0..90, fig4a)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${ROOTSIM:-$root/build/rootsim}"
out="${1:?usage: compare-solvers.sh OUT_DIR [SCENE...]}"
shift
scenes=("$@")
if ((${#scenes[@]} == 0)); then
  scenes=("$root/scenes/fig2b_waving.toml")
  for a in 0 10 20 30 40 50 60 70 80 90; do scenes+=("$root/scenes/fig2a_alpha$a.toml"); done
  scenes+=("$root/scenes/fig4a_skewing.toml")
fi
mkdir -p "$out"
TIMEFORMAT='%U %S'
for sc in "${scenes[@]}"; do
  name="$(basename "$sc" .toml)"
  for kind in dynamic newton; do
    dir="$out/${name}_$kind"
    if [ -f "$dir/summary.json" ]; then continue; fi
    t=$( { time "$bin" run "$sc" --set solver.kind=$kind --set output.vtk=false --quiet --force --out "$dir" >/dev/null; } 2>&1 )
    echo "$t" | awk '{printf "%.2f\n", $1 + $2}' > "$dir/cpu_s.txt"
    echo "$name $kind: $(cat "$dir/cpu_s.txt") s CPU" >&2
  done
done
/usr/bin/python3 - "$out" "${scenes[@]}" <<'PY'
import json, math, os, sys
out, scenes = sys.argv[1], sys.argv[2:]
rows = []
def get(d, k):
    v = d.get(k)
    return float('nan') if v is None else v
for sc in scenes:
    name = os.path.basename(sc)[:-5]
    s = {}
    for kind in ('dynamic', 'newton'):
        d = os.path.join(out, f'{name}_{kind}')
        s[kind] = json.load(open(os.path.join(d, 'summary.json')))
        s[kind]['cpu'] = float(open(os.path.join(d, 'cpu_s.txt')).read())
        step = float([l for l in open(os.path.join(d, 'scene.toml')) if l.startswith('step_h')][0].split('=')[1].split('#')[0])
    a, b = s['dynamic'], s['newton']
    def rel(k):
        x, y = get(a, k), get(b, k)
        return (y - x) / x * 100 if x and not math.isnan(x) and not math.isnan(y) else float('nan')
    snap_steps = (get(b, 'first_snap_h') - get(a, 'first_snap_h')) / step
    rows.append(dict(scene=name, pattern_dynamic=a['pattern'], pattern_newton=b['pattern'],
                     snap_dynamic_h=get(a, 'first_snap_h'), snap_newton_h=get(b, 'first_snap_h'), snap_diff_steps=snap_steps,
                     wavelength_dynamic_mm=get(a, 'wavelength_mm'), wavelength_newton_mm=get(b, 'wavelength_mm'), wavelength_diff_pct=rel('wavelength_mm'),
                     amplitude_dynamic_mm=get(a, 'amplitude_mm'), amplitude_newton_mm=get(b, 'amplitude_mm'), amplitude_diff_pct=rel('amplitude_mm'),
                     skew_dynamic_deg=abs(get(a, 'skew_deg')), skew_newton_deg=abs(get(b, 'skew_deg')),
                     skew_diff_deg=abs(get(b, 'skew_deg')) - abs(get(a, 'skew_deg')),
                     cpu_dynamic_s=a['cpu'], cpu_newton_s=b['cpu'], speedup=a['cpu'] / b['cpu'] if b['cpu'] else float('nan')))
keys = list(rows[0].keys())
with open(os.path.join(out, 'agreement.csv'), 'w') as f:
    f.write(','.join(keys) + '\n')
    for r in rows: f.write(','.join(str(r[k]) for k in keys) + '\n')
def f3(x): return '—' if isinstance(x, float) and math.isnan(x) else (f'{x:.3g}' if isinstance(x, float) else str(x))
with open(os.path.join(out, 'agreement.md'), 'w') as f:
    f.write('| scene | pattern (dyn / newton) | first snap h (dyn / newton, Δ steps) | λ mm (dyn / newton, Δ%) | A mm (dyn / newton, Δ%) | |skew| ° (dyn / newton) | CPU s (dyn / newton, ×) |\n|---|---|---|---|---|---|---|\n')
    for r in rows:
        f.write(f"| {r['scene']} | {r['pattern_dynamic']} / {r['pattern_newton']} | {f3(r['snap_dynamic_h'])} / {f3(r['snap_newton_h'])} ({f3(r['snap_diff_steps'])}) | "
                f"{f3(r['wavelength_dynamic_mm'])} / {f3(r['wavelength_newton_mm'])} ({f3(r['wavelength_diff_pct'])}) | "
                f"{f3(r['amplitude_dynamic_mm'])} / {f3(r['amplitude_newton_mm'])} ({f3(r['amplitude_diff_pct'])}) | "
                f"{f3(r['skew_dynamic_deg'])} / {f3(r['skew_newton_deg'])} | {f3(r['cpu_dynamic_s'])} / {f3(r['cpu_newton_s'])} ({f3(r['speedup'])}) |\n")
print(open(os.path.join(out, 'agreement.md')).read())
PY
# theta_tip histories of both solvers, one panel per scene (docs/img/solver_theta_tip.png is this plot);
# a root that snapped the other way with one solver is drawn mirrored (-theta), and says so
/usr/bin/python3 - "$out" "${scenes[@]}" <<'PY'
import csv, math, os, sys
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
out, scenes = sys.argv[1], sys.argv[2:]
def series(d):
    rows = list(csv.DictReader(open(os.path.join(d, 'timeseries.csv'))))
    return [float(r['time_h']) for r in rows], [float(r['theta_tip_deg']) for r in rows]
cols = 4
rws = math.ceil(len(scenes) / cols)
fig, axes = plt.subplots(rws, cols, figsize=(3.2 * cols, 2.4 * rws), squeeze=False)
for ax, sc in zip(axes.flat, scenes):
    name = os.path.basename(sc)[:-5]
    td, yd = series(os.path.join(out, f'{name}_dynamic'))
    tn, yn = series(os.path.join(out, f'{name}_newton'))
    # the mirror image is the same root: compare with the newton curve flipped when that fits better
    mirrored = sum(abs(a + b) for a, b in zip(yd, yn)) < sum(abs(a - b) for a, b in zip(yd, yn))
    if mirrored: yn = [-v for v in yn]
    ax.plot(td, yd, color='tab:blue', lw=2.2, label='dynamic')
    ax.plot(tn, yn, color='tab:orange', lw=1.0, ls='--', label='newton' + (' (mirrored)' if mirrored else ''))
    ax.set_title(name, fontsize=9)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6, loc='best')
for ax in list(axes.flat)[len(scenes):]: ax.axis('off')
for ax in axes[-1]: ax.set_xlabel('time [h]', fontsize=8)
for ax in axes[:, 0]: ax.set_ylabel('θ_tip [°]', fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(out, 'theta_tip.png'), dpi=90)
print('wrote', os.path.join(out, 'theta_tip.png'))
PY
