#!/usr/bin/env python3
"""The tables of docs/reproduction.md from the numbers behind them.

usage: scripts/reproduction-tables.py DIR

DIR holds one folder per part of `scripts/reproduce.sh --paper`, as
written by its --numbers option (docs/reproduction/paper/): PART/sweep.json
and PART/runs/NAME/summary.json. Prints Markdown, one section per part
found (cyclic parts: strain per cycle; the others: flow functions and
the peak, critical and volumetric numbers per confining pressure); means are given with their standard error over the seeds
(mean ± s.e., n samples). Python 3 standard library only.
"""
import functools
import json
import math
import os
import re
import shutil
import subprocess
import sys


def load(path):
    with open(path) as f:
        return json.load(f)


def pm(st, scale=1.0, digits=3):
    """'mean ± se' of a {mean, se, n} object."""
    if not st or st.get("mean") is None:
        return "–"
    m = st["mean"] * scale
    if st.get("se") is None:
        return "%.*g (n = %d)" % (digits, m, st["n"])
    return "%.*g ± %.2g" % (digits, m, st["se"] * scale)


def mean_se(xs):
    xs = [x for x in xs if x is not None and math.isfinite(x)]
    n = len(xs)
    if n == 0:
        return None
    m = sum(xs) / n
    se = (math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1) / n)
          if n > 1 else None)
    return {"mean": m, "se": se, "n": n}


def summaries(part):
    """name -> summary.json of every run of a part."""
    out, runs = {}, os.path.join(part, "runs")
    for name in sorted(os.listdir(runs)) if os.path.isdir(runs) else []:
        p = os.path.join(runs, name, "summary.json")
        if os.path.exists(p):
            out[name] = load(p)
    return out


def cyclic_period(part):
    s = load(os.path.join(part, "sweep.json"))
    print("\n### cyclic-period: strain gained per cycle (1e-6) against "
          "the period t0\n")
    rows = s.get("strain_accumulation") or []
    n = max(len(r["cycles"]) for r in rows)
    print("| run | verdict | " + " | ".join("c = %d" % (k + 1)
                                            for k in range(n)) + " |")
    print("|---|---|" + "---|" * n)
    for r in rows:
        print("| %s | %s | %s |" % (r["run"], r["verdict"], " | ".join(
            "%.3g" % (c["strain_increment"] * 1e6) for c in r["cycles"])))


def cyclic_mu(part):
    s = load(os.path.join(part, "sweep.json"))
    ens = s.get("ensembles") or []
    print("\n### %s: strain gained per cycle (1e-6), mean ± s.e. "
          "over the seeds\n" % os.path.basename(part))
    pick = [1, 2, 3, 5, 10, 20, 30, 40, 50]
    print("| μ | runs | verdicts (ratcheting/shakedown) | " +
          " | ".join("c = %d" % c for c in pick) + " | ε_D after the last "
          "cycle (1e-6) |")
    print("|---|---|---|" + "---|" * len(pick) + "---|")
    for e in sorted(ens, key=lambda e: e["mu"]):
        cyc = e.get("cycles") or []
        cells = [pm(cyc[c - 1]["strain_increment"], 1e6) if c <= len(cyc)
                 else "" for c in pick]
        end = pm(cyc[-1]["strain_end"], 1e6) if cyc else "–"
        v = e.get("verdicts", {})
        print("| %g | %d | %d/%d | %s | %s |" % (
            e["mu"], e["runs"], v.get("ratcheting", 0),
            v.get("shakedown", 0), " | ".join(cells), end))
    # the rate of the last third, per seed, with the creep exponent
    print("\nPer run: mean increment of the last third of the cycles "
          "(1e-6, ± s.e.), its ratio to the middle third's, and the "
          "exponent α of a fit Δ ∝ c^−α over cycles 2 to N (where all are "
          "positive).\n")
    print("| run | verdict | last third | last / middle | α |")
    print("|---|---|---|---|---|")
    for name, sm in summaries(part).items():
        cyc = [c["strain_increment"] for c in sm.get("cycles", [])]
        late, mid = sm.get("cycle_increment_late"), sm.get(
            "cycle_increment_middle")
        se = sm.get("cycle_increment_late_se")
        pts = [(math.log(k + 1), math.log(d)) for k, d in enumerate(cyc)
               if k > 0 and d > 0]
        alpha = "–"
        if len(pts) == len(cyc) - 1 and len(pts) > 2:
            mx = sum(p[0] for p in pts) / len(pts)
            my = sum(p[1] for p in pts) / len(pts)
            b = (sum((p[0] - mx) * (p[1] - my) for p in pts) /
                 sum((p[0] - mx) ** 2 for p in pts))
            alpha = "%.2f" % -b
        ratio = ("%.2f" % (late / mid) if late is not None and mid
                 else "–")
        print("| %s | %s | %s | %s | %s |" % (
            name, sm.get("verdict"),
            "%.3g ± %.2g" % (late * 1e6, (se or 0) * 1e6)
            if late is not None else "–", ratio, alpha))


def biaxial_pressure(part):
    s = load(os.path.join(part, "sweep.json"))
    print("\n### %s (mean ± s.e. over the seeds)\n" % os.path.basename(part))
    fits = [(f, state) for key, state in
            (("flow_function_ensemble", "peak"),
             ("flow_function_critical_ensemble", "critical"))
            for f in s.get(key) or []]
    if fits:  # a flow function needs more than one confining pressure
        print("Flow functions:\n")
        print("| group | state | seeds fitted | φ (deg) | tan φ | c (N/m) | "
              "e0 | n |")
        print("|---|---|---|---|---|---|---|---|")
        for f, state in fits:
            print("| %s | %s | %d | %s | %s | %s | %s | %s |" % (
                json.dumps(f["group"]), state, f["fits"], pm(f["phi_deg"]),
                pm(f["tan_phi"]), pm(f["cohesion"]), pm(f["void_ratio_e0"]),
                pm(f["void_ratio_n"])))
        print()
    print("Per confining pressure:\n")
    print("| group | runs | peak sin φ | critical sin φ (runs on a plateau) "
          "| e initial | e critical | initial slope of ε_v | dilatant "
          "slope |")
    print("|---|---|---|---|---|---|---|---|")
    sm = summaries(part)
    for e in sorted(s.get("ensembles") or [],
                    key=lambda e: (group_key(e["params"]),
                                   e["confining_pressure"])):
        names = [r["name"] for r in s["runs"]
                 if {k: v for k, v in r["params"].items() if k != "seed"}
                 == e["params"] and r["name"] in sm]
        slope0 = mean_se([sm[n].get("volumetric_slope_initial")
                          for n in names])
        slope1 = mean_se([sm[n].get("volumetric_slope_dilatant")
                          for n in names])
        print("| %s | %d | %s | %s | %s | %s | %s | %s |" % (
            json.dumps(e["params"]), e["runs"], pm(e["peak_sin_phi"]),
            pm(e["critical_sin_phi"]) + " (%d)" % (
                (e.get("critical_sin_phi") or {}).get("n") or 0),
            pm(e["void_ratio_initial"]), pm(e["void_ratio_critical"]),
            pm(slope0), pm(slope1)))
    single_sample_trend(s, sm)
    end_window_trend(s, part)


def group_key(params):
    """What a run's parameters hold besides its seed and pressures: the
    runs of one group differ only in these."""
    return json.dumps({k: x for k, x in params.items()
                       if k != "seed" and "pressure" not in k})


def one_per_pressure(by_p):
    """Every series of one value per pressure (in increasing pressure)
    from by_p: pressure -> the values of its runs."""
    series = [[]]
    for p in sorted(by_p):
        series = [x + [v] for x in series for v in by_p[p]]
    return series


def single_sample_trend(s, sm):
    """How often one sample per pressure, as a paper without seeds has,
    shows the critical friction falling with the pressure: over every
    choice of one run per pressure (runs on a critical plateau only), the
    share whose critical sin phi at the highest pressure is below that at
    the lowest, and the share that falls at every step."""
    by_p = {}
    for r in s.get("runs") or []:
        if r["name"] not in sm:
            continue
        v = (sm[r["name"]].get("critical") or {}).get("sin_phi")
        rest = group_key(r["params"])
        if v is not None:
            by_p.setdefault(rest, {}).setdefault(
                sm[r["name"]]["confining_pressure"], []).append(v)
    for rest, d in sorted(by_p.items()):
        ps = sorted(d)
        if len(ps) < 2 or max(len(v) for v in d.values()) < 2:
            continue
        series = one_per_pressure(d)
        ends = sum(1 for x in series if x[-1] < x[0])
        steps = sum(1 for x in series
                    if all(b < a for a, b in zip(x, x[1:])))
        print("\nOne sample per pressure%s (%s N/m; %s runs on a plateau): "
              "of the %d series, %d (%.0f %%) have the critical sin φ at "
              "%g below that at %g, %d fall at every step." % (
                  "" if rest == "{}" else " " + rest,
                  ", ".join("%g" % p for p in ps),
                  ", ".join(str(len(d[p])) for p in ps), len(series), ends,
                  100.0 * ends / len(series), ps[-1], ps[0], steps))


def end_window_trend(s, part):
    """The stress ratio of every run over the last quarter of its axial
    strain, on a plateau or not (what a reader of the curves' ends sees),
    from the pictures' tables (loading_curves.dat: the strain;
    stress_ratio_vs_void_ratio.dat: sin phi_m, row for row), and how often
    one run per pressure shows it falling with the pressure."""
    lc = os.path.join(part, "plots", "loading_curves.dat")
    sr = os.path.join(part, "plots", "stress_ratio_vs_void_ratio.dat")
    if not (os.path.exists(lc) and os.path.exists(sr)):
        return
    sm, groups = summaries(part), {}
    rest = {r["name"]: group_key(r["params"]) for r in s.get("runs") or []}
    ratios = dat_blocks(sr)
    for name, a in dat_blocks(lc).items():
        b = ratios.get(name)
        if not a or not b or len(a) != len(b) or name not in sm:
            continue  # (a run the pictures do not hold: the others count)
        top = max(r[0] for r in a)
        w = [rb[1] for ra, rb in zip(a, b) if ra[0] >= 0.75 * top]
        groups.setdefault(rest.get(name, "{}"), {}).setdefault(
            sm[name]["confining_pressure"], []).append(
                (sum(w) / len(w), b[-1][1]))
    for g, by_p in sorted(groups.items()):
        ps = sorted(by_p)
        if len(ps) < 2 or min(len(v) for v in by_p.values()) < 2:
            continue
        series = one_per_pressure(by_p)
        ends = sum(1 for x in series if x[-1][0] < x[0][0])
        last = sum(1 for x in series if x[-1][1] < x[0][1])
        print("\nThe stress ratio over the last quarter of the strain, "
              "every run (plateau or not)%s:\n" %
              ("" if g == "{}" else ", " + g))
        print("| p (N/m) | runs | sin φ_m, each run | mean ± s.e. |")
        print("|---|---|---|---|")
        for p in ps:
            print("| %g | %d | %s | %s |" % (
                p, len(by_p[p]), ", ".join("%.3f" % v for v, _ in by_p[p]),
                pm(mean_se([v for v, _ in by_p[p]]))))
        print("\nOne run per pressure: of the %d series, %d (%.0f %%) fall "
              "from %g to %g N/m; read at the last point of each curve, "
              "%d (%.0f %%)." % (len(series), ends, 100.0 * ends / len(series),
                                 ps[0], ps[-1], last,
                                 100.0 * last / len(series)))


def share_of(stats, kc, p):
    """What k_c adds to q at pressure p as a share of what k_c = k2 adds,
    (share, its s.e.), from stats {(k_c/k2, p): mean_se}; the two
    differences share q(0), whose error is counted once. None where a
    mean or an error is missing; exactly (kc, 0) at k_c = 0 and k2."""
    a, z, one = stats.get((kc, p)), stats.get((0, p)), stats.get((1, p))
    if not (a and z and one) or None in (a["se"], z["se"], one["se"]):
        return None
    if kc in (0, 1):
        return kc, 0.0
    add, full = a["mean"] - z["mean"], one["mean"] - z["mean"]
    se = math.hypot(math.hypot(a["se"] / full,
                               z["se"] * (add - full) / full ** 2),
                    one["se"] * add / full ** 2)
    return add / full, se


@functools.lru_cache(maxsize=None)
def part_names():
    """The parts of scripts/reproduce.sh, in its list's order."""
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        with open(os.path.join(here, "reproduce.sh")) as f:
            return tuple(line.split("|")[0] for line in f
                         if re.match(r"[a-z0-9-]+\|[0-9]+\|", line))
    except OSError:
        return ()


def part_rank(name):
    """A part's place in reproduce.sh's list (parts not listed come last,
    by name)."""
    names = part_names()
    return (names.index(name) if name in names else len(names), name)


def oc_samples(d):
    """(part folder, run) of every finished run of the over-consolidated
    parts (oc-*), each sample once: a part that ran a seed again at the
    same k_c and pressure (oc-contacts, for the contacts' outputs) is not
    a new sample, so the part first in reproduce.sh's list keeps it."""
    seen = set()
    for name in sorted(os.listdir(d), key=part_rank):
        path = os.path.join(d, name, "sweep.json")
        if not name.startswith("oc-") or not os.path.exists(path):
            continue
        for r in load(path)["runs"]:
            sample = (r.get("kc_over_k2"), r.get("confining_pressure"),
                      r["params"].get("seed"))
            if r.get("status") != "finished" or sample in seen:
                continue
            seen.add(sample)
            yield os.path.join(d, name), r


def adhesion_strength(d):
    """Luding et al. Fig. 5 bottom, read at fixed confining pressure: the
    peak deviator q = sigma_axial - sigma_lateral of the over-consolidated
    frictionless runs (parts oc-*), per k_c/k2 and pressure; what the
    adhesion adds to it, q(k_c) - q(0); and that as a share of what
    k_c = k2 adds, against the two candidate shapes: f_min (the largest
    adhesive force, k_c (k2 - k1)/(k2 + k_c) per unit overlap, shares
    0.40 and 0.67 at k_c/k2 = 0.25 and 0.5 with k1/k2 = 1/2) and k_c
    itself (0.25, 0.5). Unlike the intercept c of a Mohr-Coulomb fit,
    which extrapolates 3-4 circles to zero stress, q at each pressure is
    measured directly."""
    q = {}
    for _, r in oc_samples(d):
        pk = r.get("peak") or {}
        if pk.get("sigma_axial") is None or pk.get("sigma_lateral") is None:
            continue
        key = (r["kc_over_k2"], r["confining_pressure"])
        q.setdefault(key, []).append(
            r["peak"]["sigma_axial"] - r["peak"]["sigma_lateral"])
    kcs = sorted({k for k, _ in q})
    ps = sorted({p for _, p in q})
    if 0 not in kcs or 1 not in kcs:
        return
    print("\n## Fig. 5 bottom at fixed confining pressure (parts oc-*)\n")
    print("| k_c/k2 | f_min share | k_c share | " + " | ".join(
        "p = %g: q (n) | added | share" % p for p in ps) + " |")
    print("|---|---|---|" + "---|---|---|" * len(ps))
    stats = {k: mean_se(v) for k, v in q.items()}
    for kc in kcs:
        fmin = 2 * kc / (1 + kc)  # f_min(k_c) / f_min(k2)
        cells = []
        for p in ps:
            a, z = stats.get((kc, p)), stats.get((0, p))
            if not a:
                cells += ["–", "–", "–"]
                continue
            cell = "%.1f ± %.1f (%d)" % (a["mean"], a["se"] or 0, a["n"])
            sh = share_of(stats, kc, p)
            if sh is None:
                cells += [cell, "–", "–"]
            elif kc == 0:
                cells += [cell, "0", "0"]
            else:
                add = a["mean"] - z["mean"]
                cells += [cell, "%.1f ± %.1f" % (
                    add, math.hypot(a["se"], z["se"])),
                    "1" if kc == 1 else "%.3f ± %.3f" % sh]
        print("| %g | %.2f | %.2f | %s |" % (kc, fmin, kc, " | ".join(cells)))
    plot_shares(d, stats, kcs, ps)


def dat_blocks(path):
    """The runs' blocks of a sweep picture's table (plots/NAME.dat): {run
    name: [rows of numbers]}, in the file's order (a block's heading is
    "# NAME" or "# NAME: note")."""
    blocks, cur = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith("# columns"):
                continue
            if line.startswith("# "):
                cur = blocks.setdefault(line[2:].split(":")[0].strip(), [])
            elif line.strip() and cur is not None:
                cur.append(tuple(float(x) for x in line.split()))
    return blocks


def adhesion_window(d, lo=0.01, hi=0.05):
    """The shares of adhesion_strength from the mean deviator over axial
    strains lo..hi instead of the peak (which, as the largest value of a
    fluctuating curve, is biased up by about the fluctuation), from the
    loading curves kept (oc-kc kept them for k_c/k2 = 0.5 only). Also
    the fluctuation: the rms of q about its 21-point moving mean."""
    q, rms, curves = {}, {}, {}
    for part, r in oc_samples(d):
        dat = os.path.join(part, "plots", "loading_curves.dat")
        if os.path.exists(dat) and dat not in curves:
            curves[dat] = dat_blocks(dat)
        rows = curves.get(dat, {}).get(r["name"])
        if rows:
            w = [x[2] for x in rows if lo <= x[0] <= hi]
            if len(w) < 10:
                continue
            key = (r["kc_over_k2"], r["confining_pressure"])
            q.setdefault(key, []).append(sum(w) / len(w))
            ys = [x[2] for x in rows if x[0] > lo]
            dev = [ys[i] - sum(ys[max(0, i - 10):i + 11]) /
                   len(ys[max(0, i - 10):i + 11]) for i in range(len(ys))]
            rms.setdefault(key, []).append(
                math.sqrt(sum(x * x for x in dev) / len(dev)))
    stats = {k: mean_se(v) for k, v in q.items()}
    ps = sorted({p for _, p in q})
    print("\n## The same, mean deviator over %g-%g axial strain\n" % (lo, hi))
    print("| k_c/k2 | " + " | ".join(
        "p = %g: q (n), rms | share" % p for p in ps) + " |")
    print("|---|" + "---|---|" * len(ps))
    for kc in sorted({k for k, _ in q}):
        cells = []
        for p in ps:
            a = stats.get((kc, p))
            if not a:
                cells += ["–", "–"]
                continue
            cells.append("%.1f ± %.1f (%d), %.1f" % (
                a["mean"], a["se"] or 0, a["n"],
                sum(rms[(kc, p)]) / len(rms[(kc, p)])))
            sh = share_of(stats, kc, p)
            cells.append("%d" % kc if kc in (0, 1) else
                         "–" if sh is None else "%.3f ± %.3f" % sh)
        print("| %g | %s |" % (kc, " | ".join(cells)))


def plot_shares(d, stats, kcs, ps):
    """The shares of adhesion_strength as a picture: DIR/oc-fixed-pressure/
    shares.dat (k_c/k2, then share and its s.e. per pressure) and
    shares.png, drawn by the shares.gp kept there (if gnuplot is found)."""
    out = os.path.join(d, "oc-fixed-pressure")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "shares.dat"), "w") as f:
        f.write("# written by scripts/reproduction-tables.py from the oc-* "
                "parts\n# k_c/k2" + "".join(
                    "  share(p=%g) se" % p for p in ps) + "\n")
        for kc in kcs:
            row = ["%g" % kc]
            for p in ps:
                sh = share_of(stats, kc, p)
                row += ["?", "?"] if sh is None else \
                    ["%.5g" % sh[0], "%.3g" % sh[1]]
            f.write(" ".join(row) + "\n")
    gp = os.path.join(out, "shares.gp")
    if os.path.exists(gp) and shutil.which("gnuplot"):
        subprocess.run(["gnuplot", "shares.gp"], cwd=out, check=True)


def table_of(part):
    """The table for a part, chosen by what its sweep.json holds."""
    s = load(os.path.join(part, "sweep.json"))
    if os.path.basename(part) == "cyclic-period":
        return cyclic_period
    if s.get("strain_accumulation") and s.get("ensembles"):
        return cyclic_mu
    if s.get("ensembles"):
        return biaxial_pressure
    return None


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit(__doc__.strip().split("\n\n")[1])
    d = sys.argv[1]
    for name in sorted(os.listdir(d)):
        part = os.path.join(d, name)
        if os.path.exists(os.path.join(part, "sweep.json")):
            fn = table_of(part)
            if fn:
                fn(part)
    adhesion_strength(d)
    adhesion_window(d)


if __name__ == "__main__":
    main()
