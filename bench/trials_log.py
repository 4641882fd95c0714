#!/usr/bin/env python3
"""What the force pass's timing trials saw over a run, from the file that
DEMBOX_TRIALS_LOG names (docs/performance.md): per window of the run,
each variant's median time in the trials it ran in, and the share of the
trials after which each variant was in use.

usage:
  DEMBOX_TRIALS_LOG=T.txt dembox run ...      (or dembox bench ...)
  bench/trials_log.py T.txt [--window MIN] [--plot OUT.png]

Prints one line per window of MIN minutes (default 5) of wall clock
from the first trial. With --plot it writes OUT.dat (those lines) and
OUT.gp beside OUT.png and draws them with gnuplot (DEMBOX_GNUPLOT names
the command; without gnuplot the data and script stay): the medians
above, the shares in use below. On a host that moves a run's two vCPUs
between one L3 cache and two, the records pass's time in the trials
doubles and the blocks pass takes over where it does
(docs/performance-log.md, session 87).
"""
import argparse
import os
import statistics
import subprocess
import sys


def read(path):
    """The log's trials: (seconds since the first, variant after it,
    {variant: us})."""
    rows = []
    try:
        f = open(path)
    except OSError as e:
        sys.exit(f"{path}: {e.strerror}")
    with f:
        for n, line in enumerate(f, 1):
            w = line.split()
            if len(w) < 8 or len(w) % 2 or w[2] not in ("first", "second"):
                sys.exit(f"{path}:{n}: not a line of DEMBOX_TRIALS_LOG")
            try:
                times = {w[k]: float(w[k + 1]) for k in range(6, len(w), 2)}
                rows.append((float(w[0]), w[4], times))
            except ValueError:
                sys.exit(f"{path}:{n}: not a line of DEMBOX_TRIALS_LOG")
    if not rows:
        sys.exit(f"{path}: no trials")
    t0 = rows[0][0]
    return [(t - t0, after, times) for t, after, times in rows]


def windows(rows, minutes):
    """Per window: (start in min, trials, {variant: median us},
    {variant: share in use after the trials})."""
    names = []
    for _, after, times in rows:
        for v in list(times) + [after]:
            if v not in names:
                names.append(v)
    out = {}
    for t, after, times in rows:
        k = int(t // (60.0 * minutes))
        o = out.setdefault(k, ([], {v: [] for v in names}))
        o[0].append(after)
        for v, us in times.items():
            o[1][v].append(us)
    table = []
    for k in sorted(out):
        afters, times = out[k]
        med = {v: statistics.median(x) if x else None
               for v, x in times.items()}
        share = {v: afters.count(v) / len(afters) for v in names}
        table.append((k * minutes, len(afters), med, share))
    return names, table


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("log")
    ap.add_argument("--window", type=float, default=5.0, metavar="MIN")
    ap.add_argument("--plot", metavar="OUT.png")
    a = ap.parse_args()
    if a.window <= 0:
        sys.exit("--window: must be > 0 minutes")
    names, table = windows(read(a.log), a.window)
    head = ("# min trials " + " ".join(f"{v}_us" for v in names) + " " +
            " ".join(f"{v}_in_use" for v in names))
    lines = [head]
    for m, n, med, share in table:
        lines.append(f"{m:g} {n} " + " ".join(
            "NaN" if med[v] is None else f"{med[v]:.1f}" for v in names) +
            " " + " ".join(f"{share[v]:.3f}" for v in names))
    print("\n".join(lines))
    if not a.plot:
        return
    base = a.plot[:-4] if a.plot.endswith(".png") else a.plot
    with open(base + ".dat", "w") as f:
        f.write("\n".join(lines) + "\n")
    nv = len(names)
    dat = os.path.basename(base) + ".dat"
    png = os.path.basename(a.plot)
    top = ", \\\n     ".join(
        f"'{dat}' u 1:{3 + i} w lp pt 7 ps 0.4 t '{v}'"
        for i, v in enumerate(names))
    bottom = ", \\\n     ".join(
        f"'{dat}' u 1:{3 + nv + i} w steps t '{v}'"
        for i, v in enumerate(names))
    gp = f"""# bench/trials_log.py {os.path.basename(a.log)} --window {a.window:g}
set terminal pngcairo size 1000,700 font ',10'
set output '{png}'
set multiplot layout 2,1
set key outside right
set grid
set ylabel 'median time in the trials (us per pass)'
set yrange [0:*]
plot {top}
set xlabel 'wall clock since the first trial (min), windows of {a.window:g} min'
set ylabel 'share of trials after which in use'
set yrange [0:1]
plot {bottom}
unset multiplot
"""
    with open(base + ".gp", "w") as f:
        f.write(gp)
    cmd = os.environ.get("DEMBOX_GNUPLOT", "gnuplot")
    try:
        subprocess.run([cmd, os.path.basename(base) + ".gp"], check=True,
                       cwd=os.path.dirname(os.path.abspath(base)))
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"trials_log.py: {cmd}: {e}; the data and script are in "
              f"{base}.dat and {base}.gp", file=sys.stderr)


if __name__ == "__main__":
    main()
