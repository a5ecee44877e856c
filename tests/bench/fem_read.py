"""Reads what CalculiX wrote for a deck of `peensim export-fem` (its .inp and .dat): the dent along
NPROFILE after the relaxation step, the shot's rebound (NSHOTCENTRES' last velocities), and the
residual stress under the impact (EAXIS: the block's element column at the patch centre), each
element's integration points averaged and placed at its centroid's depth. SI units throughout."""
import re


def read_inp(path):
    """Block nodes (id -> (x, y, z) m), block elements (id -> node ids) and the EAXIS element ids."""
    nodes, elements, axis = {}, {}, []
    mode = None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("**"):
                continue
            if line.startswith("*"):
                u = line.upper()
                mode = ("node" if u.startswith("*NODE, NSET=NBLOCK") else
                        "element" if u.startswith("*ELEMENT") and "ELSET=EBLOCK" in u else
                        "axis" if u.startswith("*ELSET, ELSET=EAXIS") else None)
                continue
            fields = [x for x in line.split(",") if x.strip()]
            if mode == "node":
                nodes[int(fields[0])] = tuple(float(x) for x in fields[1:4])
            elif mode == "element":
                elements[int(fields[0])] = [int(x) for x in fields[1:]]
            elif mode == "axis":
                axis += [int(x) for x in fields]
    return nodes, elements, axis


def read_dat(path):
    """The .dat's tables: a list of (quantity, set, time, rows), rows as lists of numbers."""
    tables = []
    head = re.compile(r"^\s*(.+?)\s*\(.*\)\s*for set (\S+) and time\s+(\S+)", re.I)
    with open(path) as f:
        for line in f:
            m = head.match(line)
            if m:
                tables.append((m.group(1).strip().lower(), m.group(2).upper(), float(m.group(3)), []))
                continue
            fields = line.split()
            if tables and fields:
                try:
                    tables[-1][3].append([float(x) for x in fields])
                except ValueError:
                    pass
    return tables


def last(tables, quantity, nset):
    found = [t for t in tables if t[0].startswith(quantity) and t[1] == nset.upper()]
    return found[-1] if found else None


def dent(nodes, table):
    """Depth, diameter where the surface comes back to 0, pile-up crest diameter and height (m)."""
    pts = sorted((nodes[int(r[0])][0] + r[1], r[3]) for r in table[3])  # (deformed x, uz)
    depth = -pts[0][1]
    zero = None
    for (x0, u0), (x1, u1) in zip(pts, pts[1:]):
        if u0 < 0.0 <= u1:
            zero = 2.0 * (x0 + (x1 - x0) * (-u0) / (u1 - u0))
            break
    crest = max(pts, key=lambda p: p[1])
    return depth, zero, 2.0 * crest[0], crest[1]


def axis_profile(nodes, elements, table, component=1):
    """[(depth m, mean stress Pa)] of the EAXIS elements, shallowest first (component 1 = sxx)."""
    sums = {}
    for r in table[3]:
        e = int(r[0])
        s, n = sums.get(e, (0.0, 0))
        sums[e] = (s + r[1 + component], n + 1)
    out = []
    for e, (s, n) in sums.items():
        zc = sum(nodes[k][2] for k in elements[e][:8]) / 8.0
        out.append((-zc, s / n))
    return sorted(out)


def summarise(inp, dat, impact_speed):
    nodes, elements, _ = read_inp(inp)
    tables = read_dat(dat)
    u = last(tables, "displacements", "NPROFILE")
    v = last(tables, "velocities", "NSHOTCENTRES")
    s = last(tables, "stresses", "EAXIS")
    d = dent(nodes, u)
    return {
        "depth": d[0], "zero_diameter": d[1], "crest_diameter": d[2], "crest_height": d[3],
        "cor": v[3][0][3] / impact_speed if v else float("nan"),
        "relaxed_time": u[2],
        "sxx": axis_profile(nodes, elements, s) if s else [],
    }
