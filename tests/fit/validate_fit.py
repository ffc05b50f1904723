#!/usr/bin/env python3
"""Validation of `rootsim fit` on a synthetic trace (docs/experiments.md, "Validation").

A run with known parameters is exported to RSML, traced as a 20 px/mm plate scan would be (points every
4 px, 0.5 px of Gaussian noise, 0.1 px rounding: examples/synthetic_trace.py), and fitted. Prints one
line per free key: truth, estimate, relative error, sigma, and |error| / sigma, then the fit's goodness. With --check it exits 1
unless every key comes back within --tolerance (relative) and within --coverage sigmas of the truth.

    validate_fit.py ROOTSIM WORKDIR --scene S.toml --truth tropism.beta=0.2,tropism.twist_r_tau=0.4 \
        --free tropism.beta=0.05:0.5,tropism.twist_r_tau=0:0.8 --objective shape --steps 1900 [--check]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SYNTH = os.path.join(HERE, "..", "..", "examples", "synthetic_trace.py")


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rootsim")
    ap.add_argument("work")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--truth", required=True, help="KEY=VALUE,... of the synthetic root")
    ap.add_argument("--free", required=True)
    ap.add_argument("--objective", default="shape")
    ap.add_argument("--steps", type=int, default=1900, help="growth steps of the synthetic root")
    ap.add_argument("--budget", type=int, default=150)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--tolerance", type=float, default=0.10, help="relative error allowed for every key")
    ap.add_argument("--identifiable", default=None,
                    help="KEY,... the keys held to --tolerance (default: all); the others only to --coverage")
    ap.add_argument("--coverage", type=float, default=2.0)
    ap.add_argument("--sigma-mm", type=float, default=None,
                    help="the traced points' uncertainty the fit is told (default: the fit's, one pixel)")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--fresh", action="store_true", help="start with an empty WORKDIR (removes what an earlier call left)")
    ap.add_argument("--drop-runs", action="store_true",
                    help="once the check has passed, remove the fit's run folders (about 17 MB each, gigabytes in all); "
                         "its fit.json, tables and pictures stay")
    a = ap.parse_args()
    if a.fresh and os.path.isdir(a.work):
        shutil.rmtree(a.work)
    os.makedirs(a.work, exist_ok=True)
    truth = dict(kv.split("=") for kv in a.truth.split(","))
    run_dir = os.path.join(a.work, "truth")
    sets = ["--set", f"growth.steps={a.steps}", "--set", "output.vtk=false"]
    for k, v in truth.items():
        sets += ["--set", f"{k}={v}"]
    if not os.path.isdir(run_dir):
        run([a.rootsim, "run", a.scene, "--out", run_dir, "--quiet"] + sets)
    exported = os.path.join(a.work, "truth.rsml")
    if not os.path.exists(exported):
        run([a.rootsim, "export", run_dir, "--rsml", exported, "--quiet"])
    trace = os.path.join(a.work, "trace.rsml")
    if not os.path.exists(trace):
        run([sys.executable, SYNTH, exported, trace, "--px-per-mm", "20", "--step-px", "4", "--noise-px", "0.5",
             "--seed", str(a.seed)])
    out = os.path.join(a.work, "fit")
    t0 = time.time()
    sigma = ["--sigma-mm", str(a.sigma_mm)] if a.sigma_mm else []
    run([a.rootsim, "fit", trace, "--px-per-mm", "20", "--scene", a.scene, "--free", a.free, "--objective",
         a.objective, "-j", str(a.jobs), "--budget", str(a.budget), "--out", out, "--quiet"] + sigma)
    wall = time.time() - t0
    fit = json.load(open(os.path.join(out, "fit.json")))
    ok = True
    print(f"fit: {fit['evaluations']} runs in {wall:.1f} s wall with -j {a.jobs}; chi2 {fit['chi2']:.3g} for {fit['dof']} dof")
    for k, v in truth.items():
        t = float(v)
        b = fit["best"][k]
        err = b["value"] - t
        rel = abs(err) / abs(t)
        sig = b["sigma"]  # None (JSON null): no uncertainty, a flat direction
        z = abs(err) / sig if sig else float("inf")
        shown = f"+- {sig:.2g}" if sig else "(no uncertainty)"
        print(f"{k}: truth {t:g}, fitted {b['value']:.4g} {shown}, error {100 * rel:.1f} %, {z:.2f} sigma")
        held = a.identifiable is None or k in a.identifiable.split(",")
        if (held and rel > a.tolerance) or not z <= a.coverage:
            ok = False
    g = fit["goodness"]
    print(f"goodness: chi2 {g['chi2']:.4g} for {g['dof']} dof, p {g['p_value']:.3g}: {g['verdict']} (answer: {fit['answer']})")
    if "misfit" in fit:
        print("misfit:", fit["misfit"])
    for n in fit["notes"]:
        print("note:", n["note"])
    if a.check and not ok:
        sys.exit(f"validation failed: an estimate is off by more than {100 * a.tolerance:g} % or {a.coverage:g} sigma")
    if a.drop_runs:
        shutil.rmtree(os.path.join(out, "runs"))


if __name__ == "__main__":
    main()
