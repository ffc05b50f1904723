#!/usr/bin/env python3
"""The calibration table of a fit by group's contrasts over seeds (bench/calibrate_groups.sh's log).

Each "seed S twist_diff D SIGMA P beta_diff D SIGMA P ..." line of LOG is one plate. For a key whose truth
difference is 0 (beta; the twist too on a null plate): how often p < 0.05 and p < 0.01 (with the exact
Clopper-Pearson 95 % interval of that rate) and the mean and SD of z = difference / sigma (0 and 1 when the
sigma is calibrated). For the twist on a plate whose mutants differ: how often the difference is within
20 % of the truth, how often p < 0.01, and the z of (difference - truth) / sigma. A seed whose key is flat
(a group does not determine it) is counted apart: it makes no call.
With --rows, first a row per seed (the differences, sigmas and p-values, the verdicts and answer scales).
Usage: calibration_table.py LOG --truth-twist T [--rows]   (T: the mutants' twist; WT - mut is -T)
"""
import argparse
import math


def binom_cdf(k, n, p):
    return sum(math.comb(n, i) * p**i * (1 - p) ** (n - i) for i in range(k + 1))


def clopper_pearson(k, n, level=0.95):
    """The exact binomial interval of k successes in n trials."""
    a = (1 - level) / 2

    def solve(f):  # f increasing in p on [0, 1]; its root by bisection
        lo, hi = 0.0, 1.0
        for _ in range(80):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
        return (lo + hi) / 2

    lower = 0.0 if k == 0 else solve(lambda p: (1 - binom_cdf(k - 1, n, p)) - a)
    upper = 1.0 if k == n else solve(lambda p: a - binom_cdf(k, n, p))
    return lower, upper


def rate(k, n):
    if n == 0:
        return "–"
    lo, hi = clopper_pearson(k, n)
    return f"{k}/{n} = {100 * k / n:.1f} % [{100 * lo:.1f}, {100 * hi:.1f}]"


def zline(z):
    if len(z) < 2:
        return "–"
    m = sum(z) / len(z)
    sd = math.sqrt(sum((x - m) ** 2 for x in z) / (len(z) - 1))
    return f"{m:+.2f}, {sd:.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("log")
    ap.add_argument("--truth-twist", type=float, required=True)
    ap.add_argument("--rows", action="store_true", help="a row per seed first")
    a = ap.parse_args()
    rows = []
    for line in open(a.log):
        f = line.split()
        if not f or f[0] != "seed":
            continue
        r = {"seed": int(f[1])}
        for key, at in (("twist", f.index("twist_diff")), ("beta", f.index("beta_diff"))):
            r[key] = None if f[at + 1] in ("flat", "fixed") else tuple(float(x) for x in f[at + 1 : at + 4])
        r["verdicts"] = f[f.index("verdicts") + 1 : f.index("verdicts") + 3]
        r["chi2"] = f[f.index("chi2") + 1 : f.index("chi2") + 3]
        r["scale"] = f[f.index("answer_scale") + 1 : f.index("answer_scale") + 3]
        rows.append(r)
    rows.sort(key=lambda r: r["seed"])
    if a.rows:
        def cells(v):
            return "flat | | " if v is None else f"{v[0]:+.4f} | {v[1]:.4f} | {v[2]:.2g}"
        print("| seed | Rτ: WT − mut | σ | p | β: WT − mut | σ | p | χ² WT, mut | answer_scale WT, mut |")
        print("|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            print(f"| {r['seed']} | {cells(r['twist'])} | {cells(r['beta'])} | {', '.join(r['chi2'])} | {', '.join(r['scale'])} |")
        print()
    truth = -a.truth_twist
    print(f"{len(rows)} seeds ({min(r['seed'] for r in rows)}–{max(r['seed'] for r in rows)}); "
          f"a group's fit poor on {sum('poor' in r['verdicts'] for r in rows)}")
    print()
    print("| key (truth WT − mut) | seeds it is determined | p < 0.05 | p < 0.01 | z mean, SD | within 20 % of the truth |")
    print("|---|---|---|---|---|---|")
    for key in ("beta", "twist"):
        t = 0.0 if key == "beta" else truth
        got = [r[key] for r in rows if r[key] is not None]
        n = len(got)
        z = [(d - t) / s for d, s, _ in got if s > 0]
        p05 = sum(p < 0.05 for _, _, p in got)
        p01 = sum(p < 0.01 for _, _, p in got)
        within = "–" if t == 0 else rate(sum(abs(d - t) <= 0.2 * abs(t) for d, _, _ in got), n)
        name = "β" if key == "beta" else "Rτ"
        print(f"| {name} ({t:+g}) | {n} of {len(rows)} | {rate(p05, n)} | {rate(p01, n)} | {zline(z)} | {within} |")
    print()
    for key in ("beta", "twist"):
        got = [r[key][0] for r in rows if r[key] is not None]
        if len(got) > 1:
            m = sum(got) / len(got)
            se = math.sqrt(sum((x - m) ** 2 for x in got) / (len(got) - 1) / len(got))
            print(f"{key}: mean difference {m:+.4f} ± {se:.4f} (standard error over {len(got)} seeds)")


main()
