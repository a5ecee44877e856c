#!/usr/bin/env python3
"""LIGGGHTS reference half of the soft-sphere comparison on the "rod" ultrasonic-peening scene
(and, with --scene plate, on the "plate" scene: the rod replaced by a flat plate hung under the lid).

Two sub-commands, both driven by liggghts_rod.sh (standard library only: no numpy):

  liggghts_rod.py setup OUTDIR [--duration S] [--settle S] [--seed N] [--shots N] [--dump-every K]
                              [--scene rod|plate] [--restitution E] [--friction F]
      writes the meshes (ASCII STL, metres), the shot positions, the LIGGGHTS input deck and
      params.json (every number the parser needs, so that the deck and the parser cannot disagree).
  liggghts_rod.py parse OUTDIR [--wall-time S]
      streams the contact dumps, cuts them into contact episodes ("impacts"), writes
      OUTDIR/liggghts_stats.json and prints a table.

Units: SI everywhere inside LIGGGHTS and in the JSON (m, s, kg, Pa, m/s); the tables print mm, us
where said.
"""

import argparse
import bisect
import json
import math
import os
import random
import re
import sys

# ---------------------------------------------------------------------------------------------
# The scene (SI). Single source of truth for the deck, the meshes and the parser.
# ---------------------------------------------------------------------------------------------
CHAMBER_X = (-0.030, 0.030)      # m
CHAMBER_Y = (-0.015, 0.015)      # m
CHAMBER_Z = (0.0, 0.040)         # m: floor (sonotrode face at rest) .. lid
WALL_BOTTOM_Z = -0.001           # m: side walls reach 1 mm below the floor so that the plate,
                                 # which dips 25 um below z = 0, never opens a slit at the edges
ROD_RADIUS = 0.005               # m
ROD_AXIS_X, ROD_AXIS_Z = 0.0, 0.020   # m: axis along y
ROD_FACETS = 48                  # facets around
ROD_SEGMENTS = 10                # rings of facets along y
AMPLITUDE = 25e-6                # m, sonotrode displacement amplitude along z
PERIOD = 50e-6                   # s (20 kHz)
SHOT_DIAMETER = 0.002            # m
SHOT_DENSITY = 7800.0            # kg/m3
YOUNG = 200e9                    # Pa, every body
POISSON = 0.3
RESTITUTION = 0.9
FRICTION = 0.1
TIMESTEP = 1.5e-7                # s
SKIN = 0.0004                    # m
GRAVITY = 9.81                   # m/s2, along -z
SHOT_Z_RANGE = (0.0013, 0.0065)  # m: initial shot centres above the floor
IMPACT_LINE = 0.05               # m/s: peensim's default accuracy.impact_speed (parse only)

# The plate scene (--scene plate): the rod left out, a flat plate of 40 x 20 x 4 mm hung under the
# lid instead, centred in x and y, its top face in the lid's plane (z 36 to 40 mm). 300 shot, e 0.8,
# Coulomb 0.3 (issue 28, item 4).
PLATE_SIZE = (0.040, 0.020, 0.004)    # m, along x, y, z
PLATE_CENTER = (0.0, 0.0, 0.038)      # m
SCENE_DEFAULTS = {"rod": {"shots": 512, "restitution": RESTITUTION, "friction": FRICTION},
                  "plate": {"shots": 300, "restitution": 0.8, "friction": 0.3}}

# Mesh order in the one fix wall/gran: the dump's mesh index is this position (the part last: the
# rod or the plate).
MESHES = ["sonotrode", "walls", "rod"]


def rod_triangles():
    """Closed faceted tube, axis along y, vertices on the circle (the first vertex on top,
    +z), outward normals. No end caps: the ends lie in the side-wall planes y = +-15 mm, where a
    cap could never be touched by a shot and would only duplicate the wall there."""
    tris = []
    ys = [CHAMBER_Y[0] + (CHAMBER_Y[1] - CHAMBER_Y[0]) * j / ROD_SEGMENTS for j in range(ROD_SEGMENTS + 1)]
    ring = []
    for i in range(ROD_FACETS):
        a = 2.0 * math.pi * i / ROD_FACETS
        ring.append((ROD_AXIS_X + ROD_RADIUS * math.sin(a), ROD_AXIS_Z + ROD_RADIUS * math.cos(a)))
    for j in range(ROD_SEGMENTS):
        y0, y1 = ys[j], ys[j + 1]
        for i in range(ROD_FACETS):
            (xa, za), (xb, zb) = ring[i], ring[(i + 1) % ROD_FACETS]
            p00, p01 = (xa, y0, za), (xa, y1, za)
            p10, p11 = (xb, y0, zb), (xb, y1, zb)
            # winding chosen so that (b-a)x(c-a) points away from the axis
            tris.append((p00, p01, p10))
            tris.append((p10, p01, p11))
    return tris


def plate_triangles():
    """The plate's bottom face (normal -z, toward the sonotrode) and its four sides (outward
    normals), two triangles each. No top face: it lies in the lid's plane, where no shot can
    touch it."""
    (x0, x1), (y0, y1), (z0, z1) = [(c - h / 2.0, c + h / 2.0) for c, h in zip(PLATE_CENTER, PLATE_SIZE)]
    tris = []
    tris += quad((x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))  # bottom, normal -z
    tris += quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # x-, normal -x
    tris += quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))  # x+, normal +x
    tris += quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # y-, normal -y
    tris += quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))  # y+, normal +y
    return tris


def quad(a, b, c, d):
    """Two triangles of the quad a-b-c-d (in that winding order)."""
    return [(a, b, c), (a, c, d)]


def wall_triangles():
    """Four side walls and the lid, two triangles each (triangle t belongs to face t // 2, the
    parser uses that to tell a corner contact's two faces apart); normals into the cavity."""
    x0, x1 = CHAMBER_X
    y0, y1 = CHAMBER_Y
    z0, z1 = WALL_BOTTOM_Z, CHAMBER_Z[1]
    tris = []
    tris += quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # x = -30 mm, normal +x
    tris += quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))  # x = +30 mm, normal -x
    tris += quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # y = -15 mm, normal +y
    tris += quad((x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))  # y = +15 mm, normal -y
    tris += quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # lid, normal -z
    return tris


WALL_FACE_NAMES = ["x-", "x+", "y-", "y+", "lid"]


def sonotrode_triangles():
    """The floor, 60 x 30 mm at z = 0 (rest position), normal +z."""
    x0, x1 = CHAMBER_X
    y0, y1 = CHAMBER_Y
    z = CHAMBER_Z[0]
    return quad((x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z))


def write_ascii_stl(path, name, tris):
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        for a, b, c in tris:
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            ln = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write("  facet normal %.9e %.9e %.9e\n    outer loop\n" % tuple(x / ln for x in n))
            for p in (a, b, c):
                f.write("      vertex %.9e %.9e %.9e\n" % p)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)


def place_shots(count, seed):
    """Random sequential placement without overlap, at rest, seeded (Python's Mersenne Twister,
    so a seed gives the same positions on every machine). Centres keep 0.2 mm (half the skin)
    more than a radius from the side walls so no shot starts touching a wall."""
    r = SHOT_DIAMETER / 2.0
    margin = r + SKIN / 2.0
    lo = (CHAMBER_X[0] + margin, CHAMBER_Y[0] + margin, SHOT_Z_RANGE[0])
    hi = (CHAMBER_X[1] - margin, CHAMBER_Y[1] - margin, SHOT_Z_RANGE[1])
    rng = random.Random(seed)
    cell = SHOT_DIAMETER  # grid of one diameter: overlaps can only be with the 27 neighbour cells
    grid = {}
    pts = []
    tries = 0
    while len(pts) < count:
        tries += 1
        if tries > 1000000:
            sys.exit("setup: could not place %d shots without overlap" % count)
        p = tuple(lo[k] + (hi[k] - lo[k]) * rng.random() for k in range(3))
        c = tuple(int(math.floor(p[k] / cell)) for k in range(3))
        ok = True
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for q in grid.get((c[0] + dx, c[1] + dy, c[2] + dz), ()):
                        if sum((p[k] - q[k]) ** 2 for k in range(3)) < SHOT_DIAMETER ** 2:
                            ok = False
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            grid.setdefault(c, []).append(p)
            pts.append(p)
    return pts


# The contact model of every deck of the comparison (one material, type 1; format with young,
# poisson, restitution, friction): Hertz-Mindlin with the tangential history, E, nu, e, Coulomb's f.
CONTACT_MODEL = """fix             m1 all property/global youngsModulus peratomtype {young}
fix             m2 all property/global poissonsRatio peratomtype {poisson}
fix             m3 all property/global coefficientRestitution peratomtypepair 1 {restitution}
fix             m4 all property/global coefficientFriction peratomtypepair 1 {friction}

pair_style      gran model hertz tangential history
pair_coeff      * *
"""

DECK = """\
# LIGGGHTS 3.8 input deck, written by liggghts_rod.py setup: the "{scene}" ultrasonic shot-peening
# scene with Hertz-Mindlin contacts for every pair. SI units.
units           si
atom_style      granular
atom_modify     map array          # pair/gran/local "id" needs the atom map
boundary        f f f
newton          off
communicate     single vel yes
hard_particles  yes                # E = 200 GPa is above LIGGGHTS' default 1 GPa sanity bound

read_data       shots.data         # the box and the shot (diameter, density, position; at rest)

neighbor        {skin} bin
neigh_modify    delay 0

# One material (type 1) for shot, {scene}, walls and sonotrode; surfaces are told apart by mesh index.
""" + CONTACT_MODEL + """timestep        {dt}
fix             grav all gravity {g} vector 0.0 0.0 -1.0

fix             sonotrode all mesh/surface file meshes/sonotrode.stl type 1
fix             walls all mesh/surface file meshes/walls.stl type 1
fix             {scene} all mesh/surface file meshes/{scene}.stl type 1
# z(t) = A sin(2 pi t / P) from t = 0 (the fix is defined at step 0); the mesh velocity is set too
fix             vibrate all move/mesh mesh sonotrode wiggle amplitude 0.0 0.0 {amp} period {period}
# Mesh index in the contact output = position here: 0 sonotrode, 1 walls + lid, 2 {scene}
fix             meshwalls all wall/gran model hertz tangential history mesh n_meshes 3 meshes sonotrode walls {scene}

fix             integrate all nve/sphere

# Per-contact output (must be defined before the first run). Wall rows: contact point (3),
# particle position (3), wall velocity at the contact (3), particle velocity (3), mesh index,
# triangle index, particle id, overlap. Pair rows: positions (3+3), velocities (3+3), ids (2), a
# periodic flag, overlap.
compute         wallc all wall/gran/local pos vel id delta
compute         pairc all pair/gran/local pos vel id delta

thermo_style    custom step time atoms ke cpu
thermo          {thermo_every}
thermo_modify   lost error norm no

# Settle: the bed fluidises from rest; no contact output.
run             {settle_steps}

# Production: contact output every {dump_every} steps (one contact lasts ~40 steps).
dump            dwall all local {dump_every} wall_contacts.dump c_wallc[1] c_wallc[2] c_wallc[3] c_wallc[4] c_wallc[5] c_wallc[6] c_wallc[7] c_wallc[8] c_wallc[9] c_wallc[10] c_wallc[11] c_wallc[12] c_wallc[13] c_wallc[14] c_wallc[15] c_wallc[16]
dump            dpair all local {dump_every} pair_contacts.dump c_pairc[1] c_pairc[2] c_pairc[3] c_pairc[4] c_pairc[5] c_pairc[6] c_pairc[7] c_pairc[8] c_pairc[9] c_pairc[10] c_pairc[11] c_pairc[12] c_pairc[13] c_pairc[14] c_pairc[15] c_pairc[16]
run             {prod_steps}
"""


def cmd_setup(args):
    out = args.outdir
    os.makedirs(os.path.join(out, "meshes"), exist_ok=True)
    if not (0.0 <= args.settle < args.duration):
        sys.exit("setup: need 0 <= settle < duration")
    if args.dump_every < 1:
        sys.exit("setup: --dump-every must be >= 1")
    # dumps fire on multiples of dump_every: both ends of the production window sit on one
    k = args.dump_every
    settle_steps = int(round(args.settle / TIMESTEP / k)) * k
    prod_steps = int(round((args.duration - args.settle) / TIMESTEP / k)) * k

    write_ascii_stl(os.path.join(out, "meshes", "sonotrode.stl"), "sonotrode", sonotrode_triangles())
    write_ascii_stl(os.path.join(out, "meshes", "walls.stl"), "walls", wall_triangles())
    scene = args.scene
    defaults = SCENE_DEFAULTS[scene]
    shots = args.shots if args.shots is not None else defaults["shots"]
    restitution = args.restitution if args.restitution is not None else defaults["restitution"]
    friction = args.friction if args.friction is not None else defaults["friction"]
    part_triangles = rod_triangles() if scene == "rod" else plate_triangles()
    write_ascii_stl(os.path.join(out, "meshes", scene + ".stl"), scene, part_triangles)

    pts = place_shots(shots, args.seed)
    # read_data rather than create_atoms: one file, and the box comes with it
    box = ((CHAMBER_X[0] - 0.001, CHAMBER_X[1] + 0.001), (CHAMBER_Y[0] - 0.001, CHAMBER_Y[1] + 0.001),
           (WALL_BOTTOM_Z - 0.001, CHAMBER_Z[1] + 0.001))
    with open(os.path.join(out, "shots.data"), "w") as f:
        f.write("LIGGGHTS data file: %d shot at rest, seed %d, written by liggghts_rod.py setup (SI)\n\n"
                % (len(pts), args.seed))
        f.write("%d atoms\n%d atom types\n\n" % (len(pts), 1 if args.friction_shot_shot is None else 2))
        for (a, b), ax in zip(box, "xyz"):
            f.write("%.6f %.6f %slo %shi\n" % (a, b, ax, ax))
        # atom_style granular: id type diameter (m) density (kg/m3) x y z (m)
        f.write("\nAtoms\n\n")
        for i, p in enumerate(pts):
            f.write("%d 1 %g %g %.9e %.9e %.9e\n" % ((i + 1, SHOT_DIAMETER, SHOT_DENSITY) + p))

    deck = DECK.format(
        scene=scene, skin=SKIN, young=YOUNG, poisson=POISSON, restitution=restitution, friction=friction,
        dt=TIMESTEP, g=GRAVITY, amp=AMPLITUDE, period=PERIOD,
        thermo_every=max(1, int(round(0.005 / TIMESTEP))),
        settle_steps=settle_steps, prod_steps=prod_steps, dump_every=args.dump_every)
    if args.friction_shot_shot is not None:
        # A second material type for the meshes, the same data, so that the shot-shot pair can
        # have its own friction (a controlled variant: the rest of the deck unchanged).
        deck = deck.replace("peratomtype %s\n" % YOUNG, "peratomtype %s %s\n" % (YOUNG, YOUNG))
        deck = deck.replace("peratomtype %s\n" % POISSON, "peratomtype %s %s\n" % (POISSON, POISSON))
        deck = deck.replace("peratomtypepair 1 %s\n" % restitution, "peratomtypepair 2 %s %s %s %s\n" % ((restitution,) * 4))
        deck = deck.replace("peratomtypepair 1 %s\n" % friction,
                            "peratomtypepair 2 %s %s %s %s\n" % (args.friction_shot_shot, friction, friction, friction))
        deck = deck.replace(".stl type 1", ".stl type 2")
        assert deck.count(".stl type 2") == 3 and deck.count("peratomtypepair 2") == 2
    with open(os.path.join(out, "in." + scene), "w") as f:
        f.write(deck)

    params = {
        "scene": scene, "shots": shots, "seed": args.seed,
        "timestep_s": TIMESTEP, "dump_every_steps": args.dump_every,
        "settle_steps": settle_steps, "production_steps": prod_steps,
        "settle_s": settle_steps * TIMESTEP, "duration_s": (settle_steps + prod_steps) * TIMESTEP,
        "shot_diameter_m": SHOT_DIAMETER, "shot_density_kg_m3": SHOT_DENSITY,
        "young_pa": YOUNG, "poisson": POISSON, "restitution": restitution, "friction": friction,
        "friction_shot_shot": friction if args.friction_shot_shot is None else args.friction_shot_shot,
        "amplitude_m": AMPLITUDE, "period_s": PERIOD, "skin_m": SKIN, "gravity_m_s2": GRAVITY,
        "meshes": MESHES[:-1] + [scene], "wall_faces": WALL_FACE_NAMES,
    }
    if scene == "rod":
        params["rod"] = {"radius_m": ROD_RADIUS, "facets_around": ROD_FACETS, "segments_along": ROD_SEGMENTS,
                         "end_caps": False, "axis": "y", "x_m": ROD_AXIS_X, "z_m": ROD_AXIS_Z}
    else:
        params["plate"] = {"size_m": list(PLATE_SIZE), "center_m": list(PLATE_CENTER), "top_face": False}
    with open(os.path.join(out, "params.json"), "w") as f:
        json.dump(params, f, indent=2)
        f.write("\n")
    print("setup: wrote %s (settle %d steps, production %d steps, contact dump every %d steps)"
          % (out, settle_steps, prod_steps, args.dump_every))


# ---------------------------------------------------------------------------------------------
# Parsing
# ---------------------------------------------------------------------------------------------
def dump_frames(path):
    """Yields (timestep, list of rows as lists of strings) for each frame of a LAMMPS 'dump
    local' text file, one frame at a time (the files can be gigabytes)."""
    with open(path, "r") as f:
        readline = f.readline
        while True:
            line = readline()
            if not line:
                return
            if not line.startswith("ITEM: TIMESTEP"):
                raise ValueError("%s: unexpected line %r" % (path, line[:60]))
            step = int(readline())
            readline()                      # ITEM: NUMBER OF ENTRIES
            n = int(readline())
            readline()                      # ITEM: BOX BOUNDS
            readline(); readline(); readline()
            readline()                      # ITEM: ENTRIES ...
            rows = [readline().split() for _ in range(n)]
            yield step, rows


class Surface:
    """Accumulates the impacts (contact episodes) of one surface kind."""

    def __init__(self, name):
        self.name = name
        self.starts = []        # s, time of the first contact frame, one per impact
        self.speed_corr = []    # m/s, normal impact speed with the stored-energy correction
        self.speed_raw = []     # m/s, -(relative normal velocity) at the first contact frame
        self.delta0 = []        # m, overlap at the first contact frame
        self.durations = []     # s, episodes that both start and end inside the window
        self.frames_1 = 0       # impacts seen in exactly one frame (a hint that k is too coarse)


def percentile(sorted_vals, q):
    """Linear interpolation between closest ranks (numpy's default), q in [0, 100]."""
    if not sorted_vals:
        return None
    if len(sorted_vals) == 1:
        return sorted_vals[0]
    pos = (len(sorted_vals) - 1) * q / 100.0
    i = int(math.floor(pos))
    j = min(i + 1, len(sorted_vals) - 1)
    return sorted_vals[i] + (sorted_vals[j] - sorted_vals[i]) * (pos - i)


def mean(v):
    return sum(v) / len(v) if v else None


def stdev(v):
    if len(v) < 2:
        return None
    m = mean(v)
    return math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))


def track(frames, key_and_data, first_step, last_step, dump_every, dt, on_impact, on_end):
    """Cuts a stream of contact frames into episodes: a key (pair of bodies) present in
    consecutive frames is one episode; absent from a frame, it has ended. Episodes already in
    contact in the window's first frame are left out (they began before the window); episodes
    still open at the last frame count as impacts but get no duration."""
    open_eps = {}   # key -> [first step, last step, began inside the window]
    prev = None
    for step, rows in frames:
        if prev is None and step != first_step:
            raise ValueError("contact dump starts at step %d, expected %d" % (step, first_step))
        if prev is not None and step != prev + dump_every:
            raise ValueError("contact frames not every %d steps: %d after %d" % (dump_every, step, prev))
        seen = {}
        for row in rows:
            key, delta = key_and_data(row)
            if delta <= 0.0:
                continue        # a neighbour listed without overlap: not a contact
            # two rows for one key in one frame (the shot touches two triangles of one face):
            # keep the deeper one
            if key not in seen or delta > seen[key][0]:
                seen[key] = (delta, row)
        for key, (delta, row) in seen.items():
            ep = open_eps.get(key)
            if ep is not None and ep[1] == prev:
                ep[1] = step
                continue
            inside = step > first_step
            open_eps[key] = [step, step, inside]
            if inside:
                on_impact(key, row, step)
        for key in [key for key, ep in open_eps.items() if ep[1] != step]:
            first, last, inside = open_eps.pop(key)
            if inside:
                on_end(key, first, last)
        prev = step
    if prev is not None and prev != last_step:
        raise ValueError("contact dump ends at step %d, expected %d (run cut short?)" % (prev, last_step))


def parse_log(path):
    """Loop times of the runs in a LIGGGHTS log: list of dicts (seconds, steps, and the
    breakdown: Pair, Neigh, Comm, Outpt, Modfy, Other)."""
    runs = []
    cur = None
    loop_re = re.compile(r"^Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
    part_re = re.compile(r"^(Pair|Neigh|Comm|Outpt|Output|Modfy|Modify|Other)\s+time \(%\) = ([0-9.eE+-]+)")
    with open(path) as f:
        for line in f:
            m = loop_re.match(line)
            if m:
                cur = {"loop_s": float(m.group(1)), "procs": int(m.group(2)),
                       "steps": int(m.group(3)), "atoms": int(m.group(4)), "parts_s": {}}
                runs.append(cur)
                continue
            m = part_re.match(line)
            if m and cur is not None:
                name = {"Output": "Outpt", "Modify": "Modfy"}.get(m.group(1), m.group(1))
                cur["parts_s"][name] = float(m.group(2))
    return runs


def cmd_parse(args):
    out = args.outdir
    with open(os.path.join(out, "params.json")) as f:
        P = json.load(f)
    dt = P["timestep_s"]
    k = P["dump_every_steps"]
    s0 = P["settle_steps"]
    s1 = s0 + P["production_steps"]
    t0, t1 = s0 * dt, s1 * dt
    T = t1 - t0
    R = P["shot_diameter_m"] / 2.0
    m = P["shot_density_kg_m3"] * 4.0 / 3.0 * math.pi * R ** 3
    E_star = P["young_pa"] / (2.0 * (1.0 - P["poisson"] ** 2))   # same material on both sides
    omega = 2.0 * math.pi / P["period_s"]
    A = P["amplitude_m"]

    part = P.get("scene", "rod")
    surfaces = {name: Surface(name) for name in (part, "sonotrode", "walls", "shot-shot")}
    mesh_names = P["meshes"]
    diag = {"sonotrode_wall_velocity_max_error_m_s": 0.0, "walls_impacts_by_face": {}, "max_rows_per_frame": {"wall": 0, "pair": 0}}

    def hertz_energy(delta, r_eff):
        # J, elastic energy stored in a Hertz overlap: U = 8/15 E* sqrt(R*) delta^(5/2)
        return 8.0 / 15.0 * E_star * math.sqrt(r_eff) * max(delta, 0.0) ** 2.5

    # ---- shot-wall contacts -----------------------------------------------------------------
    # row: cp(0:3) xp(3:6) vwall(6:9) vp(9:12) mesh(12) tri(13) id(14) delta(15)
    def wall_key(row):
        mesh = int(float(row[12]))
        face = int(float(row[13])) // 2 if mesh_names[mesh] == "walls" else 0
        return (mesh, face, int(float(row[14]))), float(row[15])

    def wall_impact(key, row, step):
        v = [float(x) for x in row[:16]]
        n = [v[3] - v[0], v[4] - v[1], v[5] - v[2]]          # from the contact point to the centre
        ln = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
        n = [c / ln for c in n]
        vrel = [v[9] - v[6], v[10] - v[7], v[11] - v[8]]     # shot relative to the wall at the contact
        vn = vrel[0] * n[0] + vrel[1] * n[1] + vrel[2] * n[2]  # < 0 while approaching
        delta = v[15]
        s = surfaces[mesh_names[key[0]]]
        t = step * dt
        if mesh_names[key[0]] == "walls":
            face = P["wall_faces"][key[1]]
            diag["walls_impacts_by_face"][face] = diag["walls_impacts_by_face"].get(face, 0) + 1
        # Back to the first touch: along the overlap delta the relative normal motion gained the
        # Hertz energy U and the work of the other normal accelerations, gravity and (sonotrode)
        # the plate's own acceleration a_w = -A w^2 sin(w t), which reaches 4e5 m/s2 and is not
        # negligible: w_touch^2 = vn^2 + 2U/m* + 2 (g.n - a_w.n) delta, m* = m for a wall.
        # (Viscous damping over the few steps before the frame is not undone.)
        g_n = -P["gravity_m_s2"] * n[2]
        a_n = -A * omega * omega * math.sin(omega * t) * n[2] if mesh_names[key[0]] == "sonotrode" else 0.0
        s.starts.append(t)
        s.speed_raw.append(-vn)
        s.speed_corr.append(math.sqrt(max(vn * vn + 2.0 * hertz_energy(delta, R) / m + 2.0 * (g_n - a_n) * delta, 0.0)))
        s.delta0.append(delta)
        if mesh_names[key[0]] == "sonotrode":
            # check: LIGGGHTS' mesh velocity against the wiggle's derivative A w cos(w t)
            err = abs(v[8] - A * omega * math.cos(omega * t))
            diag["sonotrode_wall_velocity_max_error_m_s"] = max(diag["sonotrode_wall_velocity_max_error_m_s"], err)

    def wall_end(key, first, last):
        s = surfaces[mesh_names[key[0]]]
        s.durations.append((last - first + k) * dt)
        if last == first:
            s.frames_1 += 1

    # ---- shot-shot contacts -----------------------------------------------------------------
    # row: x1(0:3) x2(3:6) v1(6:9) v2(9:12) id1(12) id2(13) periodic(14) delta(15)
    def pair_key(row):
        a, b = int(float(row[12])), int(float(row[13]))
        return ((a, b) if a < b else (b, a)), float(row[15])

    def pair_impact(key, row, step):
        v = [float(x) for x in row[:16]]
        n = [v[0] - v[3], v[1] - v[4], v[2] - v[5]]          # from shot 2 to shot 1
        ln = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
        n = [c / ln for c in n]
        vrel = [v[6] - v[9], v[7] - v[10], v[8] - v[11]]
        vn = vrel[0] * n[0] + vrel[1] * n[1] + vrel[2] * n[2]
        delta = v[15]
        s = surfaces["shot-shot"]
        s.starts.append(step * dt)
        s.speed_raw.append(-vn)
        # m* = m/2, R* = R/2 for two equal shots; gravity acts on both alike
        s.speed_corr.append(math.sqrt(vn * vn + 2.0 * hertz_energy(delta, R / 2.0) / (m / 2.0)))
        s.delta0.append(delta)

    def pair_end(key, first, last):
        s = surfaces["shot-shot"]
        s.durations.append((last - first + k) * dt)
        if last == first:
            s.frames_1 += 1

    def counted(gen, which):
        for step, rows in gen:
            if len(rows) > diag["max_rows_per_frame"][which]:
                diag["max_rows_per_frame"][which] = len(rows)
            yield step, rows

    track(counted(dump_frames(os.path.join(out, "wall_contacts.dump")), "wall"), wall_key, s0, s1, k, dt,
          wall_impact, wall_end)
    track(counted(dump_frames(os.path.join(out, "pair_contacts.dump")), "pair"), pair_key, s0, s1, k, dt,
          pair_impact, pair_end)

    # ---- statistics -------------------------------------------------------------------------
    nwin = args.windows
    edges = [t0 + T * i / nwin for i in range(nwin + 1)]

    def window_of(t):
        return min(max(bisect.bisect_right(edges, t) - 1, 0), nwin - 1)

    def speed_stats(vals, starts):
        sv = sorted(vals)
        by_win = [[] for _ in range(nwin)]
        for t, x in zip(starts, vals):
            by_win[window_of(t)].append(x)
        wmeans = [mean(w) for w in by_win if w]
        se = stdev(wmeans) / math.sqrt(len(wmeans)) if len(wmeans) >= 2 else None
        return {"count": len(sv), "mean": mean(sv), "sem_batch": se,
                "p10": percentile(sv, 10), "p50": percentile(sv, 50), "p90": percentile(sv, 90),
                "min": sv[0] if sv else None, "max": sv[-1] if sv else None}

    results = {}
    for name, s in surfaces.items():
        counts = [0] * nwin
        for t in s.starts:
            counts[window_of(t)] += 1
        wrates = [c / (T / nwin) for c in counts]
        n = len(s.starts)
        results[name] = {
            "impacts": n,
            "rate_per_s": n / T,
            "rate_se_poisson_per_s": math.sqrt(n) / T,
            "rate_se_batch_per_s": (stdev(wrates) / math.sqrt(nwin)) if nwin >= 2 else None,
            "rate_by_window_per_s": wrates,
            "normal_speed_corrected_m_s": speed_stats(s.speed_corr, s.starts),
            "normal_speed_raw_m_s": speed_stats(s.speed_raw, s.starts),
            # peensim's impact line (accuracy.impact_speed, 5 cm/s): slower contacts are not impacts
            # there; the same statistics over the impacts at or above it, and how many fall below
            "impacts_below_impact_line": sum(1 for v in s.speed_corr if v < IMPACT_LINE),
            "normal_speed_corrected_above_impact_line_m_s": speed_stats(
                [v for v in s.speed_corr if v >= IMPACT_LINE], [t for t, v in zip(s.starts, s.speed_corr) if v >= IMPACT_LINE]),
            "first_frame_overlap_median_m": percentile(sorted(s.delta0), 50),
            "contact_duration_median_s": percentile(sorted(s.durations), 50),
            "contact_duration_mean_s": mean(s.durations),
            "contacts_with_duration": len(s.durations),
            "impacts_seen_in_one_frame": s.frames_1,
        }

    runs = parse_log(os.path.join(out, "log.liggghts"))
    timing = {}
    if len(runs) >= 2:
        settle_run, prod_run = runs[-2], runs[-1]
        out_s = prod_run["parts_s"].get("Outpt", 0.0)
        timing = {
            "settle_loop_s": settle_run["loop_s"], "settle_steps": settle_run["steps"],
            "production_loop_s": prod_run["loop_s"], "production_steps": prod_run["steps"],
            "production_output_s": out_s,
            # the production run's own timing (includes writing the contact dumps)
            "wall_per_sim_s_production": prod_run["loop_s"] / (prod_run["steps"] * dt),
            # the same less LIGGGHTS' "Outpt" share: the simulation alone
            "wall_per_sim_s_production_no_output": (prod_run["loop_s"] - out_s) / (prod_run["steps"] * dt),
            # the settle run writes no contact output
            "wall_per_sim_s_settle": settle_run["loop_s"] / (settle_run["steps"] * dt) if settle_run["steps"] else None,
            "atoms_at_end": prod_run["atoms"],
        }
    if args.wall_time is not None:
        timing["liggghts_process_wall_s"] = args.wall_time

    stats = {
        "source": "LIGGGHTS 3.8 (Debian liggghts), serial",
        "params": P,
        "window_s": [t0, t1],
        "window_length_s": T,
        "batch_windows": nwin,
        "impact_definition": "contact episode: a (shot, surface) or (shot, shot) key present in consecutive "
                             "contact frames (every dump_every_steps); counted if its first frame is after "
                             "the window start; walls+lid keyed per face",
        "speed_definition": "corrected = sqrt(vn^2 + 2U/m*), U = 8/15 E* sqrt(R*) delta^(5/2), vn = relative "
                            "normal velocity at the first contact frame (sonotrode: relative to the plate); "
                            "raw = -vn",
        "surfaces": results,
        "timing": timing,
        "diagnostics": diag,
    }
    with open(os.path.join(out, "liggghts_stats.json"), "w") as f:
        json.dump(stats, f, indent=2)
        f.write("\n")
    print_table(stats)


def fmt(x, scale=1.0, spec="%.3f"):
    return "-" if x is None else spec % (x * scale)


def print_table(st):
    P = st["params"]
    print()
    print("LIGGGHTS %s scene: %d shot, window %.4f..%.4f s (%.4f s), contact frames every %d steps (%.2f us)"
          % (P.get("scene", "rod"), P["shots"], st["window_s"][0], st["window_s"][1], st["window_length_s"], P["dump_every_steps"],
             P["dump_every_steps"] * P["timestep_s"] * 1e6))
    hdr = "%-10s %9s %10s %8s %8s %7s %7s %7s %7s %7s %8s %8s %9s" % (
        "surface", "impacts", "rate /s", "se_pois", "se_batch", "v mean", "v sem", "v p10", "v p50", "v p90",
        "v max", "raw p50", "t_c med")
    print(hdr)
    print("%-10s %9s %10s %8s %8s %7s %7s %7s %7s %7s %8s %8s %9s" % (
        "", "", "", "/s", "/s", "m/s", "m/s", "m/s", "m/s", "m/s", "m/s", "m/s", "us"))
    for name, r in st["surfaces"].items():
        v = r["normal_speed_corrected_m_s"]
        print("%-10s %9d %10.1f %8.1f %8s %7s %7s %7s %7s %7s %8s %8s %9s" % (
            name, r["impacts"], r["rate_per_s"], r["rate_se_poisson_per_s"], fmt(r["rate_se_batch_per_s"], 1, "%.1f"),
            fmt(v["mean"]), fmt(v["sem_batch"]), fmt(v["p10"]), fmt(v["p50"]), fmt(v["p90"]), fmt(v["max"]),
            fmt(r["normal_speed_raw_m_s"]["p50"]), fmt(r["contact_duration_median_s"], 1e6, "%.2f")))
    print("v = normal impact speed corrected for the overlap's stored energy; raw = relative normal velocity "
          "at the first contact frame")
    tm = st["timing"]
    if tm:
        print("wall time per simulated second: production %.1f s/s (incl. %.1f s of contact output; without it "
              "%.1f s/s), settle (no output) %.1f s/s"
              % (tm["wall_per_sim_s_production"], tm["production_output_s"],
                 tm["wall_per_sim_s_production_no_output"], tm["wall_per_sim_s_settle"] or float("nan")))
        if "liggghts_process_wall_s" in tm:
            print("LIGGGHTS process wall time: %.1f s" % tm["liggghts_process_wall_s"])
    d = st["diagnostics"]
    print("diagnostics: sonotrode velocity max error %.2e m/s; max contact rows per frame: wall %d, pair %d"
          % (d["sonotrode_wall_velocity_max_error_m_s"], d["max_rows_per_frame"]["wall"], d["max_rows_per_frame"]["pair"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("setup")
    a.add_argument("outdir")
    a.add_argument("--duration", type=float, default=0.35, help="simulated time, s")
    a.add_argument("--settle", type=float, default=0.15, help="time before the statistics start, s")
    a.add_argument("--seed", type=int, default=1)
    a.add_argument("--shots", type=int, default=None, help="number of shot (default 512 rod, 300 plate)")
    a.add_argument("--scene", choices=sorted(SCENE_DEFAULTS), default="rod")
    a.add_argument("--restitution", type=float, default=None, help="every pair (default 0.9 rod, 0.8 plate)")
    a.add_argument("--friction", type=float, default=None, help="Coulomb, every pair (default 0.1 rod, 0.3 plate)")
    a.add_argument("--friction-shot-shot", type=float, default=None, help="Coulomb, shot-shot only (default: --friction)")
    a.add_argument("--dump-every", type=int, default=2, help="contact output interval, steps")
    b = sub.add_parser("parse")
    b.add_argument("outdir")
    b.add_argument("--wall-time", type=float, default=None, help="LIGGGHTS process wall time, s (measured outside)")
    b.add_argument("--windows", type=int, default=10, help="batches for the batch-means standard errors")
    args = ap.parse_args()
    if args.cmd == "setup":
        cmd_setup(args)
    else:
        cmd_parse(args)


if __name__ == "__main__":
    main()
