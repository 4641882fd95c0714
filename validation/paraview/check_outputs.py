"""ParaView check of a run's snapshot series (issue 18): the particles, the
box and the contacts have the same times, from the initial to the final
state, and at every time the box is the one of the particles: their
centres lie inside it (within a radius) and it is the box of
timeseries.csv at that time.

    xvfb-run -a pvpython validation/paraview/check_outputs.py OUTDIR

Prints one line per check and exits non-zero when one fails. Not run by
CTest (ParaView is a large optional package)."""
import csv
import os
import sys

from paraview import servermanager as sm
from paraview.simple import PVDReader

out = sys.argv[1]
failed = []


def check(ok, what):
    print("%s: %s" % ("ok  " if ok else "FAIL", what))
    if not ok:
        failed.append(what)


readers = {name: PVDReader(FileName=os.path.join(out, name + ".pvd"))
           for name in ("particles", "box", "contacts")}
times = {name: list(r.TimestepValues) for name, r in readers.items()}
check(times["particles"] == times["box"] == times["contacts"],
      "particles, box and contacts have the same %d times %s ... %s"
      % (len(times["particles"]), times["particles"][:2],
         times["particles"][-1:]))
rows = list(csv.DictReader(open(os.path.join(out, "timeseries.csv"))))
t_end = float(rows[-1]["t"])
check(abs(times["particles"][0]) < 1e-12 and
      abs(times["particles"][-1] - t_end) < 1e-9,
      "the series runs from t = 0 to the last row of timeseries.csv (%.6g s)"
      % t_end)


def bounds(reader, t):
    reader.UpdatePipeline(t)
    return reader.GetDataInformation().GetBounds()


for t in (times["particles"][0], times["particles"][-1]):
    pb = bounds(readers["particles"], t)
    bb = bounds(readers["box"], t)
    data = sm.Fetch(readers["particles"])
    r = data.GetPointData().GetArray("radius")
    rmax = max(r.GetValue(k) for k in range(r.GetNumberOfTuples())) if r \
        else 0.0
    inside = all(pb[2 * a] >= bb[2 * a] - rmax and
                 pb[2 * a + 1] <= bb[2 * a + 1] + rmax for a in range(3))
    check(inside, "t = %.6g s: particle centres %s inside the box %s "
          "(within the largest radius %.3g m)"
          % (t, [round(v, 6) for v in pb], [round(v, 6) for v in bb], rmax))
    row = min(rows, key=lambda w: abs(float(w["t"]) - t))
    if abs(float(row["t"]) - t) > 1e-9:
        print("--  : t = %.6g s: no timeseries.csv row then (its first is at "
              "t = %s s, one output interval in): box size not compared"
              % (t, rows[0]["t"]))
        continue
    dims = [bb[2 * a + 1] - bb[2 * a] for a in range(3)]
    want = [float(row["Lx"]), float(row["Ly"]), float(row["Lz"])]
    same = all(abs(d - w) <= 1e-6 * max(w, 1e-12) or w == 0.0
               for d, w in zip(dims, want))
    check(same, "t = %.6g s: box sizes %s = timeseries.csv's Lx, Ly, Lz %s"
          % (t, [round(v, 9) for v in dims], [round(v, 9) for v in want]))

print("check_outputs: %s" % ("all ok" if not failed else
                             "%d failed" % len(failed)))
sys.exit(1 if failed else 0)
