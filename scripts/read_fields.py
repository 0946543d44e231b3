"""Read the contact pressure p(r) of external solvers' field files through meshio.

spherecontact runs this as a subprocess (Debian's /usr/bin/python3, python3-meshio, python3-h5py)
to read the VTU (FreeFEM) and XDMF (dolfinx) files its decks write, and plots p(r) from them.

usage: read_fields.py --radius R --window W --out OUT.csv FIELD...
  R      sphere radius, in the field files' length unit
  W      largest r kept (the contact zone and a margin)
Writes OUT.csv with columns file,r,pressure: the points on the spherical surface (|x - centre|
within 1e-7 R of R), r <= W, sorted by r, one block per FIELD in the order given.
Exit codes: 0 done; 3 a field file is missing, unreadable, has no `pressure`, no surface points,
or a non-finite value (the message says which).
"""
import argparse
import csv
import sys

import numpy as np
import meshio


def read(path):
    """The points and point data of a VTU, or of the last step of an XDMF time series."""
    if path.endswith(".xdmf"):
        # dolfinx writes XDMF time series, which meshio.read does not accept
        with meshio.xdmf.TimeSeriesReader(path) as reader:
            points, _ = reader.read_points_cells()
            data = {}
            for k in range(reader.num_steps):
                _, point_data, _ = reader.read_data(k)
                data.update(point_data)
        return points, data
    mesh = meshio.read(path)
    return mesh.points, mesh.point_data


def surface_pressure(path, radius, window):
    points, data = read(path)
    if "pressure" not in data:
        raise ValueError(f"{path}: no `pressure` field (has {sorted(data)})")
    p = np.asarray(data["pressure"], dtype=float).reshape(len(points), -1)[:, 0]
    r, z = points[:, 0], points[:, 1]
    on_sphere = np.abs(np.hypot(r, z - radius) - radius) < 1e-7 * radius
    keep = on_sphere & (r <= window) & (z < radius)
    if not keep.any():
        raise ValueError(f"{path}: no point on the spherical surface within r <= {window}")
    rows = sorted(zip(r[keep], p[keep]))
    if not np.all(np.isfinite(np.array(rows))):
        raise ValueError(f"{path}: non-finite pressure or coordinate")
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--radius", type=float, required=True)
    ap.add_argument("--window", type=float, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("fields", nargs="+")
    args = ap.parse_args()
    try:
        blocks = [(f, surface_pressure(f, args.radius, args.window)) for f in args.fields]
    except Exception as e:  # noqa: BLE001 - every failure is reported, with its file
        print(f"read_fields: {e}", file=sys.stderr)
        sys.exit(3)
    with open(args.out, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["file", "r", "pressure"])
        for name, rows in blocks:
            for r, p in rows:
                out.writerow([name, repr(float(r)), repr(float(p))])


if __name__ == "__main__":
    main()
