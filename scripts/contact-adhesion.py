#!/usr/bin/env python3
"""The adhesion a sheared cohesive packing holds, read from its contacts.

usage: scripts/contact-adhesion.py PART_DIR OUT_DIR

PART_DIR is a sweep of biaxial2d-paper runs with Luding's law over
contact.kc (part `oc-contacts` of scripts/reproduce.sh: over-consolidated
at 1000 N/m, sheared at 100 N/m, mu = 0, output.dump_interval > 0 so that
every run has dump_local.lammpstrj with the contacts' dmax). For each run
and three moments, the end of the first stage (consolidated), the start
of the loading stage and the peak of the stress ratio (the dump frames
nearest to them; the peak from summary.json's peak strain), it measures
over the particle pairs:

  Z           2 N_pairs/N, the coordination
  dmax        the mean largest overlap reached (m)
  fmin        the mean largest attraction f_min = kc (k2 - k1) dmax/(k2 + kc)
              (N; Luding et al., section 2.2)
  s_cap       sum f_min |b| / (2 A): the isotropic Love-Weber stress of the
              contacts' largest attractions (N/m), the tensile strength
              the network would have if every contact were pulled to f_min
  s_ten       the same sum over the pairs in tension, of their actual -fn
  tension     the share of the pairs in tension
  q_ten       the deviator (axial minus lateral) of the Love-Weber stress of
              the pairs in tension (N/m; compression positive, so their
              share of the strength), q_comp that of the pairs in
              compression: q = q_comp + q_ten for frictionless pairs
  adhesive    the share of s_ten carried by pairs on the adhesive branch
              (delta <= delta_min = (k2 - k1) dmax/(k2 + kc), f = -kc delta:
              a tension proportional to kc at a given overlap), the rest
              on the un-/re-loading line k2 (delta - delta_0)

and writes OUT_DIR/contacts.json (every run's numbers), OUT_DIR/shares.dat
(each measure's share of k_c = k2's, mean and standard error over the
seeds) and OUT_DIR/shares.png through OUT_DIR/shares.gp (gnuplot; copied
from docs/reproduction/paper/oc-contacts/ when OUT_DIR has none).
The numbers of docs/reproduction.md's "Fig. 5 bottom: what the contacts
hold" come from this script.
"""
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys

# the run's files through the project's Python module (it reads them
# without loading libdembox.so); dump_local.lammpstrj is streamed below,
# frame by frame, as each run's is some 80-90 MB
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "python"))
import dembox  # noqa: E402


def config_value(cfg, key):
    """The number of `key = value;` inside the contact group of config.cfg."""
    m = re.search(r"\bcontact\s*=\s*\{(.*?)\};", cfg, re.S)
    body = m.group(1) if m else cfg
    m = re.search(r"\b%s\s*=\s*([-+0-9.eE]+)\s*;" % re.escape(key), body)
    if not m:
        raise SystemExit("contact-adhesion.py: no contact.%s in config.cfg" % key)
    return float(m.group(1))


def top_value(cfg, key):
    m = re.search(r"^%s\s*=\s*([-+0-9.eE]+)\s*;" % re.escape(key), cfg, re.M)
    if not m:
        raise SystemExit("contact-adhesion.py: no %s in config.cfg" % key)
    return float(m.group(1))


def frames(path):
    """Yield (step, box lengths, header names, rows) of dump_local.lammpstrj."""
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                return
            if not line.startswith("ITEM: TIMESTEP"):
                continue
            step = int(f.readline())
            f.readline()
            n = int(f.readline())
            f.readline()
            box = [tuple(map(float, f.readline().split())) for _ in range(3)]
            names = f.readline().split()[2:]
            rows = [f.readline().split() for _ in range(n)]
            yield step, [hi - lo for lo, hi in box], names, rows


def measure(rows, names, L, k1, k2, kc, n_particles, axis):
    col = {c: k for k, c in enumerate(names)}
    if "dmax" not in col:
        raise SystemExit("contact-adhesion.py: dump_local has no dmax column "
                         "(a dembox older than the history columns)")
    area = L[0] * L[1]
    npair = ten = 0
    sum_dmax = s_cap = s_ten = s_adh = 0.0
    ax = "xyz".index(axis)
    lat = 1 - ax if ax < 2 else 0  # the lateral axis of the 2D sample
    q = {"ten": 0.0, "comp": 0.0}
    for r in rows:
        if int(r[col["id2"]]) < 0:  # wall contact
            continue
        npair += 1
        dmax = float(r[col["dmax"]])
        b = math.hypot(float(r[col["bx"]]), float(r[col["by"]]))
        fmin = kc * (k2 - k1) * dmax / (k2 + kc)
        sum_dmax += dmax
        s_cap += fmin * b
        fn = float(r[col["fn"]])
        nv = [float(r[col["n" + a]]) for a in "xyz"]
        q["ten" if fn < 0 else "comp"] += fn * b * (nv[ax] ** 2 - nv[lat] ** 2)
        if fn < 0:
            ten += 1
            s_ten += -fn * b
            dmin = (k2 - k1) * dmax / (k2 + kc)
            if float(r[col["delta"]]) <= dmin * (1 + 1e-6):
                s_adh += -fn * b
    return {
        "Z": 2.0 * npair / n_particles,
        "dmax": sum_dmax / npair,
        "fmin": kc * (k2 - k1) * (sum_dmax / npair) / (k2 + kc),
        "s_cap": s_cap / (2 * area),
        "s_ten": s_ten / (2 * area),
        "tension": ten / npair,
        "adhesive": s_adh / s_ten if s_ten > 0 else 0.0,
        "q_ten": q["ten"] / area,
        "q_comp": q["comp"] / area,
    }


def one_run(d):
    cfg = open(os.path.join(d, "config.cfg")).read()
    k1, k2, kc = (config_value(cfg, k) for k in ("k1", "k2", "kc"))
    dt = top_value(cfg, "time_step")
    summ = json.load(open(os.path.join(d, "summary.json")))
    ts = dembox.timeseries(d)
    stage = int(summ["loading_stage"])
    axis = summ.get("axis", "y")
    L = ts["L" + axis]
    k0 = next(k for k, s in enumerate(ts["stage"]) if int(s) == stage)
    peak = summ.get("peak") or {}
    if peak.get("strain") is None:
        return None
    tp = next((ts["t"][k] for k in range(k0, len(L))
               if 1.0 - L[k] / L[k0] >= peak["strain"]), None)
    if tp is None:
        return None
    # the end of the consolidation: the last sample of stage 0
    k1st = next((k for k, s_ in enumerate(ts["stage"]) if int(s_) >= 1), k0)
    want = {"consolidated": ts["t"][max(k1st - 1, 0)],
            "start": ts["t"][max(k0 - 1, 0)], "peak": tp}
    best = {w: (math.inf, None) for w in want}
    n_particles = None
    for step, box, names, rows in frames(os.path.join(d, "dump_local.lammpstrj")):
        t = step * dt
        for w, tw in want.items():
            # the peak: the nearest frame; the ends of the stages: the
            # last frame not after them (the next stage changes the state)
            if w != "peak" and t > tw + 0.5 * dt:
                continue
            if abs(t - tw) < best[w][0]:
                best[w] = (abs(t - tw), (t, box, names, rows))
    with open(os.path.join(d, "dump.lammpstrj")) as f:
        for line in f:
            if line.startswith("ITEM: NUMBER OF ATOMS"):
                n_particles = int(f.readline())
                break
    out = {"kc_over_k2": kc / k2, "seed": re.search(r"seed=(\d+)", d).group(1),
           "peak_sin_phi": peak.get("sin_phi"), "peak_strain": peak["strain"],
           "sigma_axial": peak.get("sigma_axial"),
           "sigma_lateral": peak.get("sigma_lateral")}
    for w in want:
        _, (t, box, names, rows) = best[w]
        m = measure(rows, names, box, k1, k2, kc, n_particles, axis)
        m["t"] = t
        m["t_wanted"] = want[w]
        out[w] = m
    return out


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__.split("\n\n")[1])
    part, outdir = sys.argv[1], sys.argv[2]
    runs = []
    rdir = os.path.join(part, "runs")
    if not os.path.isdir(rdir):
        raise SystemExit("contact-adhesion.py: %s: no runs/ folder (not a "
                         "sweep)" % part)
    for name in sorted(os.listdir(rdir)):
        d = os.path.join(rdir, name)
        if os.path.isfile(os.path.join(d, "summary.json")):
            r = one_run(d)
            if r:
                r["run"] = name
                runs.append(r)
    if not runs:
        raise SystemExit("contact-adhesion.py: no run of %s has finished "
                         "with a peak" % part)
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, "contacts.json"), "w") as f:
        json.dump(runs, f, indent=1)
    seeds = sorted({r["seed"] for r in runs})
    kcs = sorted({r["kc_over_k2"] for r in runs})
    top = max(kcs)

    def share(q, moment):
        """Per seed: q at k_c over q at the largest k_c; mean, s.e."""
        out = {}
        for kc in kcs:
            v = []
            for s in seeds:
                a = [r for r in runs if r["seed"] == s and r["kc_over_k2"] == kc]
                b = [r for r in runs if r["seed"] == s and r["kc_over_k2"] == top]
                if a and b:
                    x = a[0][moment][q] if moment else a[0][q]
                    y = b[0][moment][q] if moment else b[0][q]
                    v.append(x / y if y else math.nan)
            m = statistics.mean(v) if v else math.nan
            se = statistics.stdev(v) / math.sqrt(len(v)) if len(v) > 1 else math.nan
            out[kc] = (m, se, len(v))
        return out

    def deviator(r):
        return r["sigma_axial"] - r["sigma_lateral"]

    for r in runs:
        r["q_peak"] = deviator(r)
    # the added deviator: q(kc) - q(0), per seed
    for r in runs:
        ref = [x for x in runs if x["seed"] == r["seed"] and x["kc_over_k2"] == 0]
        r["dq_peak"] = r["q_peak"] - ref[0]["q_peak"] if ref else math.nan
    print("| k_c/k2 | moment | Z | mean dmax (µm) | mean f_min (N) | s_cap (N/m) "
          "| s_ten (N/m) | pairs in tension | s_ten on the adhesive branch "
          "| q_comp (N/m) | q_ten (N/m) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for kc in kcs:
        for moment in ("consolidated", "start", "peak"):
            sel = [r[moment] for r in runs if r["kc_over_k2"] == kc]

            def ms(q, scale=1.0):
                v = [x[q] * scale for x in sel]
                m = statistics.mean(v)
                se = statistics.stdev(v) / math.sqrt(len(v)) if len(v) > 1 else 0
                return "%.4g ± %.2g" % (m, se)
            print("| %g | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                kc, moment, ms("Z"), ms("dmax", 1e6), ms("fmin"), ms("s_cap"),
                ms("s_ten"), ms("tension"), ms("adhesive"), ms("q_comp"),
                ms("q_ten")))
    shares = {
        "dq_peak": share("dq_peak", None),
        "s_cap_start": share("s_cap", "start"),
        "s_cap_peak": share("s_cap", "peak"),
        "s_ten_peak": share("s_ten", "peak"),
        "Z_peak": share("Z", "peak"),
        "fmin_peak": share("fmin", "peak"),
        "q_ten_peak": share("q_ten", "peak"),
    }
    order = list(shares)
    with open(os.path.join(outdir, "shares.dat"), "w") as f:
        f.write("# written by scripts/contact-adhesion.py; share of k_c = k2's "
                "(mean, s.e. over %d seeds)\n# k_c/k2 %s\n"
                % (len(seeds), " ".join("%s se" % q for q in order)))
        for kc in kcs:
            f.write("%g %s\n" % (kc, " ".join(
                "%.5g %.3g" % (shares[q][kc][0], shares[q][kc][1]
                               if not math.isnan(shares[q][kc][1]) else 0)
                for q in order)))
    print()
    print("| k_c/k2 | f_min's share | " + " | ".join(order) + " |")
    print("|---|---|" + "---|" * len(order))
    for kc in kcs:
        print("| %g | %.3f | %s |" % (kc, 2 * kc / (1 + kc), " | ".join(
            "%.3f ± %.3f" % shares[q][kc][:2] for q in order)))
    gp = os.path.join(outdir, "shares.gp")
    kept = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs",
                        "reproduction", "paper", "oc-contacts", "shares.gp")
    if not os.path.exists(gp) and os.path.exists(kept):
        shutil.copy(kept, gp)
    if os.path.exists(gp):
        try:
            subprocess.run(["gnuplot", "shares.gp"], cwd=outdir, check=True)
        except (OSError, subprocess.CalledProcessError) as e:
            print("contact-adhesion.py: shares.png not drawn: %s" % e,
                  file=sys.stderr)


if __name__ == "__main__":
    main()
