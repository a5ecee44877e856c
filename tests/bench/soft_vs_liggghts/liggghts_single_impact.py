#!/usr/bin/env python3
"""One 2 mm steel shot thrown at a still flat mesh wall in LIGGGHTS 3.8 (no gravity), the rebound
printed: the controlled single-impact probe of the soft-sphere comparison (README.md beside this
file, "The plate scene").

    liggghts_single_impact.py OUTDIR --vn V --vt V [--restitution E] [--friction F]

The shot touches the wall 1 um after the start, approaching at vn (m/s) along -z with vt (m/s) along
+x and no spin; E 200 GPa, nu 0.3 on both sides, `gran model hertz tangential history` as in the
scene decks, time step 1.5e-9 s (a hundredth of the scenes': the integration is not in question
here). Prints the velocity and spin after the contact and, from the contact dump written every
step, the approach read as the scenes' parser reads it (liggghts_rod.py: the first frame's normal
velocity corrected for the overlap's Hertz energy). Needs liggghts on the PATH; standard library.
"""
import argparse
import math
import os
import subprocess

import liggghts_rod as L

DT = 1.5e-9  # s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--vn", type=float, required=True, help="approach speed, m/s")
    ap.add_argument("--vt", type=float, default=0.0, help="tangential speed, m/s")
    ap.add_argument("--restitution", type=float, default=0.8)
    ap.add_argument("--friction", type=float, default=0.3)
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    R = L.SHOT_DIAMETER / 2.0
    gap = 1e-6  # m
    L.write_ascii_stl(os.path.join(a.outdir, "floor.stl"), "floor",
                      L.quad((-0.01, -0.01, 0), (0.01, -0.01, 0), (0.01, 0.01, 0), (-0.01, 0.01, 0)))
    with open(os.path.join(a.outdir, "shot.data"), "w") as f:
        f.write("one shot\n\n1 atoms\n1 atom types\n\n-0.01 0.01 xlo xhi\n-0.01 0.01 ylo yhi\n-0.002 0.01 zlo zhi\n\n"
                "Atoms\n\n1 1 %g %g 0 0 %.12e\n" % (L.SHOT_DIAMETER, L.SHOT_DENSITY, R + gap))
    steps = int(round((gap / a.vn + 30e-6) / DT))
    deck = ("""units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
hard_particles yes
read_data shot.data
neighbor {skin} bin
neigh_modify delay 0
""" + L.CONTACT_MODEL + """timestep {dt}
fix floor all mesh/surface file floor.stl type 1
fix wall all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor
fix integrate all nve/sphere
velocity all set {vt:.12g} 0 {vz:.12g}
compute wallc all wall/gran/local pos vel id delta
dump d all local 1 contacts.dump c_wallc[1] c_wallc[2] c_wallc[3] c_wallc[4] c_wallc[5] c_wallc[6] c_wallc[7] c_wallc[8] c_wallc[9] c_wallc[10] c_wallc[11] c_wallc[12] c_wallc[13] c_wallc[14] c_wallc[15] c_wallc[16]
dump f all custom {steps} final.dump id vx vy vz omegax omegay omegaz
dump_modify f format "%d %.12g %.12g %.12g %.12g %.12g %.12g"
run {steps}
""").format(skin=L.SKIN, young=L.YOUNG, poisson=L.POISSON, restitution=a.restitution, friction=a.friction, dt=DT,
           vt=a.vt, vz=-a.vn, steps=steps)
    with open(os.path.join(a.outdir, "in.single"), "w") as f:
        f.write(deck)
    with open(os.path.join(a.outdir, "screen.txt"), "w") as out:
        subprocess.run(["liggghts", "-in", "in.single", "-log", "log.single", "-echo", "none"], cwd=a.outdir,
                       stdout=out, stderr=subprocess.STDOUT, check=True)
    with open(os.path.join(a.outdir, "final.dump")) as f:
        last = f.read().split("ITEM: ATOMS")[-1].split("\n")[1].split()
    vx, vy, vz, wx, wy, wz = (float(x) for x in last[1:7])
    m = L.SHOT_DENSITY * 4.0 / 3.0 * math.pi * R ** 3
    E_star = L.YOUNG / (2.0 * (1.0 - L.POISSON ** 2))
    first = None
    for step, rows in L.dump_frames(os.path.join(a.outdir, "contacts.dump")):
        rows = [r for r in rows if float(r[15]) > 0.0]
        if rows:
            first = (step, [float(x) for x in rows[0]])
            break
    print("LIGGGHTS single impact: vn %.6g m/s, vt %.6g m/s, e %g, f %g" % (a.vn, a.vt, a.restitution, a.friction))
    print("after: vn %.9g m/s (e_eff %.6f), vt %.9g m/s, spin %.9g rad/s, contact point vt - R w = %.6g m/s"
          % (vz, vz / a.vn, vx, wy, vx - R * wy))
    if a.vt:
        print("tangential loss dvt = %.9g m/s = %.6f x Coulomb's f (1 + e) vn" % (a.vt - vx, (a.vt - vx) / (a.friction * (1 + a.restitution) * a.vn)))
    if first:
        step, v = first
        delta = v[15]
        vn_frame = v[11] - v[8]
        corrected = math.sqrt(vn_frame ** 2 + 2.0 * 8.0 / 15.0 * E_star * math.sqrt(R) * delta ** 2.5 / m)
        print("read as the scenes' parser reads it: first frame (step %d) overlap %.4g m, raw %.9g m/s, corrected %.9g m/s"
              % (step, delta, -vn_frame, corrected))


if __name__ == "__main__":
    main()
