"""Read the contact pressure p(r) of external solvers' field files through meshio.

spherecontact runs this as a subprocess (Debian's /usr/bin/python3, python3-meshio, python3-h5py)
to read the VTU (FreeFEM) and XDMF (dolfinx) files its decks write, and plots p(r) from them.

usage: read_fields.py --radius R --window W --out OUT.csv FIELD...
  R      sphere radius, in the field files' length unit
  W      largest r kept (the contact zone and a margin)
Writes OUT.csv with columns file,r,pressure,gap: the points on the spherical surface (|x - centre|
within 1e-7 R of R), r <= W, sorted by r, one block per FIELD in the order given; gap = z + u_z
is the deformed surface's height above the contact plane (negative: penetration).
Exit codes: 0 done; 3 a field file is missing, unreadable, has no `pressure`, no surface points,
or a non-finite value: one line on stderr, `read_fields: FILE: what is wrong`. The line never
quotes the file (its values, its field names, meshio's words about it): a field file may come
from elsewhere (docs/security.md, "Deck folders").
"""
import argparse
import csv
import sys

import numpy as np
import meshio


def read(path):
    """The points and point data of a VTU, or of the last step of an XDMF time series."""
    if path.endswith(".xdmf"):
        # dolfinx writes each function as its own temporal collection, which meshio.read does
        # not accept and TimeSeriesReader reads only the last of: read every collection's last step
        with meshio.xdmf.TimeSeriesReader(path) as reader:
            points, _ = reader.read_points_cells()
            data = {}
            for grid in reader.domain:
                if grid.get("GridType") == "Collection":
                    reader.collection = list(grid)
                    _, point_data, _ = reader.read_data(len(reader.collection) - 1)
                    data.update(point_data)
        return points, data
    mesh = meshio.read(path)
    return mesh.points, mesh.point_data


class FieldError(Exception):
    """What is wrong with a field file, in this script's own words."""


def surface_pressure(path, radius, window):
    try:
        points, data = read(path)
    # meshio.read ends with sys.exit(1) on a file it cannot read; its message may quote the
    # file: only the kind of failure is kept
    except (Exception, SystemExit) as e:  # noqa: BLE001
        raise FieldError(f"not a VTU or XDMF file that meshio reads ({type(e).__name__})") from e
    for name in ("pressure", "u"):
        if name not in data:
            raise FieldError(f"no `{name}` field")
    p = np.asarray(data["pressure"], dtype=float).reshape(len(points), -1)[:, 0]
    r, z = points[:, 0], points[:, 1]
    on_sphere = np.abs(np.hypot(r, z - radius) - radius) < 1e-7 * radius
    keep = on_sphere & (r <= window) & (z < radius)
    if not keep.any():
        raise FieldError(f"no point on the spherical surface within r <= {window}")
    u = np.asarray(data["u"], dtype=float).reshape(len(points), -1)
    gap = z + u[:, 1]
    rows = sorted(zip(r[keep], p[keep], gap[keep]))
    if not np.all(np.isfinite(np.array(rows))):
        raise FieldError("non-finite pressure or coordinate")
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--radius", type=float, required=True)
    ap.add_argument("--window", type=float, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("fields", nargs="+")
    args = ap.parse_args()
    blocks = []
    for f in args.fields:
        try:
            blocks.append((f, surface_pressure(f, args.radius, args.window)))
        except FieldError as e:
            print(f"read_fields: {f}: {e}", file=sys.stderr)
            sys.exit(3)
        except Exception as e:  # noqa: BLE001 - every failure is reported, with its file
            print(f"read_fields: {f}: unreadable ({type(e).__name__})", file=sys.stderr)
            sys.exit(3)
    with open(args.out, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["file", "r", "pressure", "gap"])
        for name, rows in blocks:
            for r, p, g in rows:
                out.writerow([name, repr(float(r)), repr(float(p)), repr(float(g))])


if __name__ == "__main__":
    main()
