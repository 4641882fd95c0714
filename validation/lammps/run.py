#!/usr/bin/env python3
"""Cross-validation of dembox's contact law against LAMMPS.

Runs the same cases in both codes, with the same law and parameters, and
prints the agreement as Markdown (docs/validation.md records it):

  packing   3375 spheres relaxed in six frictionless walls (dembox bench's
            packing), 1000 steps at rest, then 2 % oedometric compression
            by the z-max wall (cosine profile over 0.4 s); mu = 0 and 0.5.
            LAMMPS is also run against itself with another neighbour skin,
            which measures how fast the packing's chaos separates two runs
            that differ only in round-off.
  sphere    one sphere launched without spin on a frictional floor under
            gravity, at 1 mm/s (it sticks) and at 0.1 m/s (it slides, then
            rolls at 5/7 of its speed).
  pair      two spheres colliding obliquely, one spinning.
  classic   the packing's positions with every diameter set to 9.6 mm
            (overlaps of up to a few per cent), mu = 0.5, one step from
            rest: against gran/hooke/history, whose mass-normalised
            dashpots equal ours when every pair has the same reduced mass,
            and against granular. Isolates the definitions in which the
            two LAMMPS styles differ (docs/validation.md).

The law (David et al.'s material at the papers' time step): linear spring
k = 5000 N/m with dashpot gamma_n = 0.05 kg/s, tangential spring k_t =
1000 N/m with history and dashpot gamma_t = 0.005 kg/s, Coulomb friction
mu, background damping gamma_b = 0.001 kg/s on translation only, dt =
2e-5 s. LAMMPS: pair_style granular hooke ... damping velocity with
tangential linear_history (gamma_t = 0.1 gamma_n), fix wall/gran granular
with the same model, fix viscous, fix nve/sphere.

Needs Debian's lammps package (lmp) and a build of this tree (dembox and
dembox_case in build/). Not run by CTest. Usage:

  validation/lammps/run.py [--work DIR] [--build DIR] [--dembox-case PATH]
                           [--cases packing,sphere,pair,classic]
                           [--mus 0,0.5] [--plots DIR]

--dembox-case runs another build of the dembox side (for example one of
an older commit) against the same LAMMPS runs. --plots writes the
pictures (gnuplot) into DIR.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

K, GN, KT, XGT, DT, GB = 5000.0, 0.05, 1000.0, 0.1, 2e-5, 0.001
GT = XGT * GN  # 0.005 kg/s
HOLD, STEPS, STRAIN, DURATION, EVERY = 1000, 20000, 0.02, 0.4, 500


def die(msg):
    sys.exit("run.py: " + msg)


def run(cmd, out=None, cwd=None):
    with open(out, "w") if out else open(os.devnull, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.PIPE, cwd=cwd,
                           text=True)
    if r.returncode != 0:
        die("%s failed:\n%s" % (" ".join(cmd), r.stderr[-2000:]))


# ------------------------------------------------------------ data files

def read_data(path):
    """Atoms (id, diameter, density, x, y, z) and the box of a data file."""
    box, atoms, vel, section = {}, {}, {}, None
    for line in open(path):
        s = line.split("#")[0].strip()
        if not s:
            continue
        w = s.split()
        if len(w) == 4 and w[2].endswith("lo") and w[3].endswith("hi"):
            box[w[2][0]] = (float(w[0]), float(w[1]))
        elif w[0] in ("Atoms", "Velocities"):
            section = w[0]
        elif section == "Atoms" and len(w) >= 7:
            atoms[int(w[0])] = [float(v) for v in w[2:7]]
        elif section == "Velocities" and len(w) >= 7:
            vel[int(w[0])] = [float(v) for v in w[1:7]]
    return box, atoms, vel


def write_data(path, box, atoms, vel, comment):
    """atom_style sphere, ids 1..N in order, 17 digits."""
    ids = sorted(atoms)
    with open(path, "w") as f:
        f.write("%s\n\n%d atoms\n1 atom types\n\n" % (comment, len(ids)))
        for a in "xyz":
            f.write("%.17g %.17g %slo %shi\n" % (box[a][0], box[a][1], a, a))
        f.write("\nAtoms # sphere\n\n")
        for n, i in enumerate(ids, 1):
            f.write("%d 1 %s\n" % (n, " ".join("%.17g" % v for v in atoms[i])))
        f.write("\nVelocities\n\n")
        for n, i in enumerate(ids, 1):
            v = vel.get(i, [0.0] * 6)
            f.write("%d %s\n" % (n, " ".join("%.17g" % x for x in v)))


def sphere_mass(d, rho):
    return math.pi / 6.0 * d ** 3 * rho


# ------------------------------------------------------------- the runs

WALLS = [("xlo", "xplane %.17g NULL", 2), ("xhi", "xplane NULL %.17g", 2),
         ("ylo", "yplane %.17g NULL", 3), ("yhi", "yplane NULL %.17g", 3),
         ("zlo", "zplane %.17g NULL", 4), ("zhi", "zplane NULL %.17g", 4)]


def lammps_input(data, box, mu, wall_mu, gz, gb, hold, steps, every, skin,
                 dump, track, meff=None):
    """With meff (kg), the pair style is gran/hooke/history with its
    mass-normalised dashpots set to gamma/meff: the same law for pairs of
    that reduced mass only, but with the classic style's torque lever
    arm a_i and plain projection of the spring."""
    model = ("hooke %.17g %.17g tangential linear_history %.17g "
             "%.17g %%s damping velocity" % (K, GN, KT, XGT))
    if meff:
        pair = ["pair_style gran/hooke/history %.17g %.17g %.17g %.17g "
                "%.17g 1" % (K, KT, GN / meff, GT / meff, mu),
                "pair_coeff * *"]
    else:
        pair = ["pair_style granular",
                "pair_coeff * * " + model % ("%.17g" % mu)]
    L = ["units si", "atom_style sphere", "atom_modify map array",
         "boundary f f f", "comm_modify vel yes",
         "read_data %s" % data,
         "neighbor %.17g bin" % skin,
         "neigh_modify delay 0 every 1 check yes"] + pair + [
         "timestep %.17g" % DT,
         "fix integ all nve/sphere"]
    if gb > 0:
        L.append("fix bg all viscous %.17g" % gb)
    if gz != 0:
        L.append("fix grav all gravity %.17g vector 0 0 -1" % -gz)
    pos = [box["x"][0], box["x"][1], box["y"][0], box["y"][1], box["z"][0],
           box["z"][1]]
    wall = "fix w%s all wall/gran granular " + model % ("%.17g" % wall_mu)
    for k, (name, plane, _) in enumerate(WALLS):
        L.append(wall % name + " " + plane % pos[k] + " contacts")
    L += ["compute ke all ke", "compute er all erotate/sphere",
          "compute cn all contact/atom", "compute z all reduce ave c_cn",
          "compute pv all property/atom vx vy vz omegax omegay omegaz",
          "variable zhi equal %.17g" % box["z"][1]]
    for name, _, col in WALLS:
        L.append("compute f%s all reduce sum f_w%s[%d]" % (name, name, col))
    for c, q in enumerate(["vx", "vy", "vz", "wx", "wy", "wz"], 1):
        L.append("variable %s equal c_pv[%d][%d]" % (q, track, c))
    L += ["thermo_style custom step c_ke c_er " +
          " ".join("c_f" + n for n, _, _ in WALLS) +
          " c_z v_zhi v_vx v_vy v_vz v_wx v_wy v_wz",
          "thermo_modify format float %.12g norm no",
          "thermo %d" % every]
    if dump:
        L += ["dump d all custom 1 %s id x y z vx vy vz omegax omegay omegaz"
              % dump, "dump_modify d format float %.17g sort id first no",
              "run 1", "undump d", "run %d" % (hold - 1)]
    else:
        L.append("run %d" % hold)
    if steps:
        A = -0.5 * STRAIN * (box["z"][1] - box["z"][0])
        L += ["unfix wzhi",
              (wall % "zhi") + " zplane NULL %.17g wiggle z %.17g %.17g "
              "contacts" % (box["z"][1], A, 2 * DURATION),
              "variable zhi equal %.17g+%.17g-%.17g*cos(%.17g*(step-%d)*%.17g)"
              % (box["z"][1], A, A, math.pi / DURATION, hold, DT),
              "run %d" % steps]
    return "\n".join(L) + "\n"


def parse_thermo(log):
    """Thermo rows of a LAMMPS log as dicts keyed like the dembox CSV."""
    names = ["step", "e_kin", "e_rot", "f_xlo", "f_xhi", "f_ylo", "f_yhi",
             "f_zlo", "f_zhi", "coordination", "zhi", "vx", "vy", "vz", "wx",
             "wy", "wz"]
    rows, on = {}, False
    for line in open(log):
        w = line.split()
        if w[:2] == ["Step", "c_ke"]:
            on = True
            continue
        if on and w and w[0] == "Loop":
            on = False
            continue
        if on and len(w) == len(names):
            r = dict(zip(names, map(float, w)))
            r["f_xhi"], r["f_yhi"], r["f_zhi"] = (-r["f_xhi"], -r["f_yhi"],
                                                  -r["f_zhi"])
            rows[int(r["step"])] = r
    return rows


def parse_csv(path):
    rows = {}
    for r in csv.DictReader(open(path)):
        rows[int(r["step"])] = {k: float(v) for k, v in r.items()}
    return rows


def read_dump(path):
    """id -> (x y z vx vy vz wx wy wz) of a LAMMPS dump or a dembox_case
    dump (the ITEM lines are skipped)."""
    out = {}
    for line in open(path):
        w = line.split()
        if len(w) == 10 and not line.startswith("ITEM"):
            try:
                out[int(w[0])] = [float(v) for v in w[1:]]
            except ValueError:
                pass
    return out


class Case:
    def __init__(self, a, work):
        self.a, self.work = a, work

    def dembox(self, tag, data, extra):
        out = os.path.join(self.work, "dembox_%s.csv" % tag)
        run([self.a.dembox_case, data] + [str(x) for x in extra], out)
        return parse_csv(out)

    def lammps(self, tag, data, box, **kw):
        inp = os.path.join(self.work, "lammps_%s.in" % tag)
        log = os.path.join(self.work, "lammps_%s.log" % tag)
        open(inp, "w").write(lammps_input(data, box, **kw))
        run(["lmp", "-in", inp, "-log", log, "-screen", "none"],
            cwd=self.work)
        return parse_thermo(log)


# ---------------------------------------------------------- comparisons

def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def step_one(d_path, l_path):
    """Largest difference of velocities and spins after one step, relative
    to the largest value of each; where LAMMPS's spins are all zero (a
    frictionless packing) the spins' absolute difference, rad/s, and
    whether it is absolute."""
    d, l = read_dump(d_path), read_dump(l_path)
    if set(d) != set(l):
        die("the step-1 dumps hold different atoms")
    dv = max(abs(d[i][k] - l[i][k]) for i in d for k in (3, 4, 5))
    vm = max(abs(l[i][k]) for i in l for k in (3, 4, 5))
    dw = max(abs(d[i][k] - l[i][k]) for i in d for k in (6, 7, 8))
    wm = max(abs(l[i][k]) for i in l for k in (6, 7, 8))
    return dv / vm, (dw / wm if wm > 0 else dw), wm == 0


def sigma_zz(r, area):
    return 0.5 * (r["f_zlo"] + r["f_zhi"]) / area


def packing(a, work):
    """The packing: dembox bench's relaxed, frictionless packing in walls."""
    cache = os.path.join(work, "cache")
    run([a.dembox, "bench", "--n", "3375", "--steps", "1", "--threads", "1",
         "--cache-dir", cache, "--quiet"])
    src = [f for f in os.listdir(cache) if f.endswith(".data")]
    if len(src) != 1:
        die("expected one packing in %s" % cache)
    box, atoms, vel = read_data(os.path.join(cache, src[0]))
    data = os.path.join(work, "pack.data")
    write_data(data, box, atoms, vel,
               "dembox bench packing, 3375 spheres, walls = box, ids sorted")
    return data, box


def case_packing(a, work, C, results):
    data, box = packing(a, work)
    area = (box["x"][1] - box["x"][0]) * (box["y"][1] - box["y"][0])
    Lz = box["z"][1] - box["z"][0]
    print("\n## Packing: 3375 spheres, 1000 steps at rest, then 2 % "
          "oedometric compression\n")
    print("| mu | run | velocities after 1 step | spins after 1 step | "
          "sigma_zz, largest up to 1 % strain | sigma_zz at 2 % | "
          "Z at 2 % (this run, LAMMPS) | E_kin + E_rot at 1 %, at 2 % "
          "(this run / LAMMPS) |")
    print("|---|---|---|---|---|---|---|---|")
    for mu in a.mus:
        tag = "mu%g" % mu
        kw = dict(mu=mu, wall_mu=0.0, gz=0.0, gb=GB, hold=HOLD, steps=STEPS,
                  every=EVERY, track=1)
        ld = os.path.join(work, "lammps_%s.step1" % tag)
        dd = os.path.join(work, "dembox_%s.step1" % tag)
        L = C.lammps(tag, data, box, skin=0.001, dump=ld, **kw)
        L2 = C.lammps(tag + "_skin", data, box, skin=0.0005, dump=None, **kw)
        D = C.dembox(tag, data, ["--mu", mu, "--hold", HOLD, "--steps", STEPS,
                                 "--strain", STRAIN, "--duration", DURATION,
                                 "--every", EVERY, "--dump", 1, dd])
        v1, w1, w_abs = step_one(dd, ld)

        def eps(k):
            return (box["z"][1] - L[k]["zhi"]) / Lz

        def at(e):  # the compression row closest to strain e
            return min((k for k in L if k > HOLD), key=lambda k:
                       abs(eps(k) - e))

        for name, other, s1 in (("dembox / LAMMPS", D, (v1, w1)),
                                ("LAMMPS skin 0.5 mm / 1 mm", L2, None)):
            early = max(rel(sigma_zz(other[k], area), sigma_zz(L[k], area))
                        for k in L if k > HOLD and eps(k) <= 0.01)
            k1, k2 = at(0.01), at(0.02)
            ek = ["%.3g" % ((other[k]["e_kin"] + other[k]["e_rot"]) /
                            (L[k]["e_kin"] + L[k]["e_rot"])) for k in (k1, k2)]
            print("| %g | %s | %s | %s | %.2g | %.2g | %.3f, %.3f | %s |" % (
                mu, name, "%.2g" % s1[0] if s1 else "",
                ("%.2g rad/s (LAMMPS's all 0)" if w_abs else "%.2g") % s1[1]
                if s1 else "", early,
                rel(sigma_zz(other[k2], area), sigma_zz(L[k2], area)),
                other[k2]["coordination"], L[k2]["coordination"],
                ", ".join(ek)))
        results[tag] = (D, L, L2, box)


def sphere_data(path, v0):
    a, rho = 5e-3, 2000.0
    m = sphere_mass(2 * a, rho)
    z = a - m * 9.81 / K
    box = {"x": (0.0, 0.1), "y": (0.0, 0.1), "z": (0.0, 0.1)}
    write_data(path, box, {1: [2 * a, rho, 0.02, 0.05, z]},
               {1: [v0, 0, 0, 0, 0, 0]}, "one sphere on the floor")
    return box


def case_sphere(a, work, C, results):
    print("\n## One sphere launched without spin on a floor (wall mu = 0.4, "
          "gravity, 1 s)\n")
    print("| v0 | gamma_t | dembox v/v0 | LAMMPS v/v0 | dembox a w/v0 | "
          "LAMMPS a w/v0 | largest difference of v over the run / v0 |")
    print("|---|---|---|---|---|---|---|")
    for v0 in (1e-3, 0.1):
        tag = "sphere_v%g" % v0
        data = os.path.join(work, tag + ".data")
        box = sphere_data(data, v0)
        kw = dict(mu=0.5, wall_mu=0.4, gz=-9.81, gb=0.0, hold=50000,
                  steps=0, every=100, track=1, skin=0.001, dump=None)
        L = C.lammps(tag, data, box, **kw)
        D = C.dembox(tag, data, ["--wall-mu", 0.4, "--gravity", -9.81,
                                 "--gamma-b", 0, "--hold", 50000,
                                 "--every", 100])
        end = max(L)
        dv = max(abs(D[s]["vx"] - L[s]["vx"]) for s in L)
        print("| %g m/s | %g kg/s | %.6f | %.6f | %.6f | %.6f | %.2g |" % (
            v0, GT, D[end]["vx"] / v0, L[end]["vx"] / v0,
            5e-3 * D[end]["wy"] / v0, 5e-3 * L[end]["wy"] / v0, dv / v0))
        results[tag] = (D, L)


def case_pair(a, work, C, results):
    print("\n## Two spheres colliding obliquely (radii 5 and 4 mm, 0.1 m/s, "
          "impact parameter 0.5, the second spinning at 40 rad/s)\n")
    print("| mu | quantity | dembox | LAMMPS granular | difference / v0 | "
          "LAMMPS gran/hooke/history | difference / v0 |")
    print("|---|---|---|---|---|---|---|")
    rho, v0 = 2000.0, 0.1
    box = {"x": (-0.1, 0.1), "y": (-0.1, 0.1), "z": (-0.1, 0.1)}
    for mu in a.mus:
        tag = "pair_mu%g" % mu
        data = os.path.join(work, tag + ".data")
        write_data(data, box, {1: [0.01, rho, -5.1e-3, 0.0, 0.0],
                               2: [0.008, rho, 4.1e-3, 4.5e-3, 0.0]},
                   {1: [v0, 0, 0, 0, 0, 0], 2: [0, 0, 0, 0, 0, 40.0]},
                   "oblique pair")
        kw = dict(mu=mu, wall_mu=0.0, gz=0.0, gb=0.0, hold=2000, steps=0,
                  every=2000, track=2, skin=0.001, dump=None)
        L = C.lammps(tag, data, box, **kw)
        m1, m2 = sphere_mass(0.01, rho), sphere_mass(0.008, rho)
        H = C.lammps(tag + "_hh", data, box, meff=m1 * m2 / (m1 + m2), **kw)
        D = C.dembox(tag, data, ["--mu", mu, "--gamma-b", 0, "--hold", 2000,
                                 "--every", 2000, "--track", 2])
        end = max(L)
        for q, scale in (("vx", 1), ("vy", 1), ("wz", 4e-3)):
            d, l, h = (X[end][q] * scale for X in (D, L, H))
            print("| %g | sphere 2: %s%s | %.9g | %.9g | %.2g | %.9g | %.2g |"
                  % (mu, q, " (x a)" if scale != 1 else "", d, l,
                     abs(d - l) / v0, h, abs(d - h) / v0))
        results[tag] = (D, L, H)


def case_classic(a, work, C, results):
    box, atoms, vel = read_data(packing(a, work)[0])
    d, rho = 0.0096, 2000.0
    for i in atoms:
        atoms[i][0], atoms[i][1] = d, rho
    data = os.path.join(work, "classic.data")
    write_data(data, box, atoms, vel, "the packing, every diameter 9.6 mm")
    meff = 0.5 * sphere_mass(d, rho)
    print("\n## One step from rest, monodisperse (d = 9.6 mm, overlaps up to "
          "a few per cent), mu = 0.5\n")
    print("| against | velocities after 1 step | spins after 1 step |")
    print("|---|---|---|")
    dd = os.path.join(work, "dembox_classic.step1")
    C.dembox("classic", data, ["--mu", 0.5, "--hold", 1, "--every", 1,
                               "--dump", 1, dd])
    for name, m in (("gran/hooke/history", meff), ("granular", None)):
        ld = os.path.join(work, "lammps_classic_%s.step1" % name[:4])
        C.lammps("classic_" + name[:4], data, box, mu=0.5, wall_mu=0.0,
                 gz=0.0, gb=GB, hold=1, steps=0, every=1, skin=0.001,
                 dump=ld, track=1, meff=m)
        v1, w1, w_abs = step_one(dd, ld)
        print("| LAMMPS %s | %.2g | %s |" % (
            name, v1, ("%.2g rad/s (LAMMPS's all 0)" if w_abs else "%.2g") % w1))


def plots(results, outdir):
    if not shutil.which("gnuplot"):
        die("gnuplot is needed for --plots")
    os.makedirs(outdir, exist_ok=True)
    tmp = tempfile.mkdtemp()
    for tag in ("mu0", "mu0.5"):
        if tag not in results:
            continue
        D, L, L2, box = results[tag]
        area = (box["x"][1] - box["x"][0]) * (box["y"][1] - box["y"][0])
        Lz = box["z"][1] - box["z"][0]
        with open(os.path.join(tmp, tag + ".dat"), "w") as f:
            for s in sorted(L):
                if s in D and s in L2:
                    eps = (box["z"][1] - L[s]["zhi"]) / Lz
                    f.write("%g %g %g %g %g %g %g %g\n" % (
                        s * DT, 100 * eps, sigma_zz(D[s], area),
                        sigma_zz(L[s], area), sigma_zz(L2[s], area),
                        D[s]["e_kin"] + D[s]["e_rot"],
                        L[s]["e_kin"] + L[s]["e_rot"],
                        L2[s]["e_kin"] + L2[s]["e_rot"]))
    png = os.path.join(outdir, "lammps_packing.png")
    gp = """set terminal pngcairo size 1200,800 font ",11"
set output '%s'
set multiplot layout 2,2
set key top left
set grid
set xlabel 'axial strain (%%)'
set ylabel 'σ_{zz} (Pa)'
set title 'frictionless (mu = 0)'
plot '%s/mu0.dat' u 2:3 w l lw 3 t 'dembox', '' u 2:4 w l lw 1.5 t 'LAMMPS', '' u 2:5 w l dt 2 t 'LAMMPS, other skin'
set title 'mu = 0.5'
plot '%s/mu0.5.dat' u 2:3 w l lw 3 t 'dembox', '' u 2:4 w l lw 1.5 t 'LAMMPS', '' u 2:5 w l dt 2 t 'LAMMPS, other skin'
set logscale y
set format y '%%.0e'
set xlabel 'time (s)'
set ylabel 'E_{kin} + E_{rot} (J)'
set title 'frictionless: kinetic energy'
plot '%s/mu0.dat' u 1:6 w l lw 3 t 'dembox', '' u 1:7 w l lw 1.5 t 'LAMMPS', '' u 1:8 w l dt 2 t 'LAMMPS, other skin'
set title 'mu = 0.5: kinetic energy'
plot '%s/mu0.5.dat' u 1:6 w l lw 3 t 'dembox', '' u 1:7 w l lw 1.5 t 'LAMMPS', '' u 1:8 w l dt 2 t 'LAMMPS, other skin'
unset multiplot
""" % (png, tmp, tmp, tmp, tmp)
    subprocess.run(["gnuplot"], input=gp, text=True, check=True)
    print("\nplot: %s" % png)
    shutil.rmtree(tmp)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--work", help="folder for inputs, logs and outputs "
                   "(default: a new temporary folder, kept)")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--dembox-case", help="the dembox_case binary (default: "
                   "BUILD/dembox_case)")
    p.add_argument("--cases", default="packing,sphere,pair,classic")
    p.add_argument("--mus", default="0,0.5",
                   help="friction coefficients of the packing and pair cases")
    p.add_argument("--plots", help="write the pictures into this folder")
    p.add_argument("--replot", action="store_true", help="only redraw the "
                   "pictures from the packing runs kept in --work")
    a = p.parse_args()
    a.dembox = os.path.join(a.build, "dembox")
    a.dembox_case = a.dembox_case or os.path.join(a.build, "dembox_case")
    a.mus = [float(m) for m in a.mus.split(",")]
    for exe in (a.dembox, a.dembox_case):
        if not os.access(exe, os.X_OK):
            die("%s: not built (cmake --build build)" % exe)
    if not shutil.which("lmp"):
        die("lmp not found: apt-get install lammps")
    work = a.work or tempfile.mkdtemp(prefix="dembox-lammps.")
    os.makedirs(work, exist_ok=True)
    work = os.path.abspath(work)
    print("# dembox against LAMMPS (work folder %s; dembox side %s)"
          % (work, a.dembox_case))
    C, results = Case(a, work), {}
    if a.replot:
        box = read_data(os.path.join(work, "pack.data"))[0]
        for mu in a.mus:
            tag = "mu%g" % mu
            results[tag] = (parse_csv(os.path.join(work, "dembox_%s.csv" % tag)),
                            parse_thermo(os.path.join(work,
                                                      "lammps_%s.log" % tag)),
                            parse_thermo(os.path.join(
                                work, "lammps_%s_skin.log" % tag)), box)
        plots(results, a.plots or ".")
        return
    cases = a.cases.split(",")
    for name, fn in (("packing", case_packing), ("sphere", case_sphere),
                     ("pair", case_pair), ("classic", case_classic)):
        if name in cases:
            fn(a, work, C, results)
    if a.plots:
        plots(results, a.plots)


if __name__ == "__main__":
    main()
