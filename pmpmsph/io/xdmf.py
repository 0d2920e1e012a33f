"""XDMF sidecar of a snapshot file, so ParaView (or VisIt) opens a run directly.

``write_xdmf("RUN.h5")`` writes ``RUN.xdmf``: a temporal collection with one Polyvertex grid
per snapshot (``Time`` = the snapshot time), geometry from the ``x`` dataset (always 3
components) and one node-centred attribute per field, ``x`` included, every DataItem
pointing into the HDF5 file by a relative path (``RUN.h5:/snapshots/000003/sigma``), so the
pair can be moved together. Only metadata is read from the HDF5 file, never particle data.

The Polyvertex topology points to an explicit connectivity 0..N-1 (``/xdmf/polyvertex/N``,
written by the SnapshotWriter once per particle count): the XDMF2 reader would generate it,
but the XDMF3 reader of ParaView builds no cells without it (points with no cells do not
render). Snapshots with no particles are left out of the sidecar.

Reading the sidecar with meshio. ``meshio.xdmf.TimeSeriesReader`` reads the geometry and
topology once, from the first grid (``read_points_cells()``), and per step only the
attributes (``read_data(k)``). That is why ``x`` is declared a second time, as a ``Vector``
attribute of every grid (the same HDF5 dataset as the Geometry: one more XML element per
snapshot, no byte more in the HDF5 file; ParaView shows it as one more point array):
``read_data(k)`` returns step k's own positions as ``point_data["x"]``; the points of
``read_points_cells()`` are those of the first snapshot only. Rows are not in the same order
from one snapshot to the next (each rank writes its own particles at its offset, and
particles migrate between ranks), so match particles of different steps by
``point_data["gid"]`` (a default field of ``[output] fields``; a sidecar of snapshots
without ``gid`` logs a warning), never by row. Rows are not sorted by gid when written: that
would need a global redistribution or a scattered HDF5 selection at every snapshot, and
output time is a measured cost of a run. ``meshio.read("RUN.xdmf")`` cannot read the file
(it fails with ``Unknown section 'Grid'``): it reads exactly one Uniform grid and no
temporal collection, which ParaView needs for the time series. For one mesh per snapshot use
``python -m pmpmsph vtu RUN`` (VTU files that ``meshio.read`` opens, plus a ``.pvd``), or
read the HDF5 file directly with :func:`pmpmsph.io.read_snapshot`.

Attribute types by dataset shape: (N,) Scalar, (N, 3) Vector, (N, 3, 3) or (N, 9) Tensor,
(N, 6) Tensor6, other (N, k) Matrix. Tensors are stored in their natural (N, 3, 3) shape and
declared with ``Dimensions="N 3 3"``; the readers take the 9 values of a particle as one
9-component tuple (row-major: xx, xy, xz, yx, ...). A symmetric (N, 6) Tensor6 is in the
XDMF order xx, xy, xz, yy, yz, zz (VTK's XDMF2 reader expands it to 9 components; the XDMF3
reader keeps 6). NumberType/Precision follow the stored dtype (Float 4 for a
single-precision run). Fields of other ranks or dtypes are left out of the sidecar (they
stay in the HDF5 file).
"""
import argparse
import logging
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

from .h5files import GROUP, TOPOLOGY, open_h5, xdmf_path_for

log = logging.getLogger("pmpmsph")
_warned = set()


def number_type(dtype):
    """(NumberType, Precision) of a numpy dtype for an XDMF DataItem, or None."""
    dtype = np.dtype(dtype)
    kind = {"f": "Float", "i": "Int", "u": "UInt"}.get(dtype.kind)
    if kind is None or dtype.itemsize not in (1, 2, 4, 8):
        return None
    if kind == "Float" and dtype.itemsize not in (4, 8):
        return None
    if kind == "UInt" and dtype.itemsize == 1:
        kind = "UChar"
    elif kind == "Int" and dtype.itemsize == 1:
        kind = "Char"
    return kind, str(dtype.itemsize)


def attribute_type(shape):
    """XDMF AttributeType for a dataset of the given (global) shape, or None."""
    trailing = tuple(shape[1:])
    if trailing == ():
        return "Scalar"
    if trailing == (3,):
        return "Vector"
    if trailing in ((3, 3), (9,)):
        return "Tensor"
    if trailing == (6,):
        return "Tensor6"
    if len(trailing) == 1:
        return "Matrix"
    return None


def _data_item(parent, ref, shape, dtype):
    ntype, precision = number_type(dtype)
    item = ET.SubElement(parent, "DataItem", {
        "Dimensions": " ".join(str(int(d)) for d in shape),
        "NumberType": ntype,
        "Precision": precision,
        "Format": "HDF",
    })
    item.text = ref
    return item


def _warn_once(key, message):
    if key not in _warned:
        _warned.add(key)
        log.warning(message)


def build_xdmf(h5path, xdmf_path=None, cache=None):
    """The XDMF document (an ElementTree) describing every snapshot of ``h5path``.

    ``cache`` (a dict kept by the caller between calls for the same pair of paths) holds the
    Grid element of each snapshot already described, so a running simulation only reads the
    metadata of its new snapshots.
    """
    h5path = os.path.abspath(os.fspath(h5path))
    xdmf_path = os.path.abspath(xdmf_path or xdmf_path_for(h5path))
    rel = os.path.relpath(h5path, os.path.dirname(xdmf_path)).replace(os.sep, "/")

    root = ET.Element("Xdmf", {"Version": "3.0"})
    domain = ET.SubElement(root, "Domain")
    series = ET.SubElement(domain, "Grid", {
        "Name": "particles", "GridType": "Collection", "CollectionType": "Temporal"})
    with open_h5(h5path, "r") as f:
        if GROUP not in f:
            raise ValueError(f"{h5path} is not a pmpmsph snapshot file (no /{GROUP} group)")
        for name in sorted(f[GROUP].keys()):
            if cache is not None and name in cache:
                if cache[name] is not None:
                    series.append(cache[name])
                continue
            grid = _snapshot_grid(f, name, h5path, rel)
            if grid is not None:
                series.append(grid)
            if cache is not None:
                cache[name] = grid
    return ET.ElementTree(root)


def _snapshot_grid(f, name, h5path, rel):
    """The Grid element of one snapshot, or None when it has nothing to show."""
    grp = f[GROUP][name]
    if "x" not in grp or tuple(grp["x"].shape[1:]) != (3,):
        _warn_once((h5path, name, "x"), f"{h5path}: snapshot {name} has no (N, 3) 'x' "
                   "dataset; left out of the XDMF sidecar")
        return None
    n = int(grp["x"].shape[0])
    if n == 0:  # nothing to draw, and readers fail on empty arrays
        return None
    grid = ET.Element("Grid", {"Name": f"step_{name}", "GridType": "Uniform"})
    ET.SubElement(grid, "Time", {"Value": repr(float(grp.attrs["time"]))})
    topology = ET.SubElement(grid, "Topology", {
        "TopologyType": "Polyvertex", "NumberOfElements": str(n), "NodesPerElement": "1"})
    conn = f.get(f"{TOPOLOGY}/{n}")
    if conn is not None:
        _data_item(topology, f"{rel}:/{TOPOLOGY}/{n}", conn.shape, conn.dtype)
    geometry = ET.SubElement(grid, "Geometry", {"GeometryType": "XYZ"})
    _data_item(geometry, f"{rel}:/{GROUP}/{name}/x", grp["x"].shape, grp["x"].dtype)
    if "gid" not in grp:
        _warn_once((h5path, "no gid"), f"{h5path}: snapshot {name} has no 'gid' field, so its "
                   "particles cannot be matched with those of other snapshots (rows are not "
                   "in the same order); keep 'gid' in [output] fields")
    # x too (after the Geometry, in the written order): meshio's TimeSeriesReader reads the
    # Geometry of the first grid only, and the attributes of every grid
    for field in grp.keys():
        dset = grp[field]
        atype = attribute_type(dset.shape)
        if atype is None or number_type(dset.dtype) is None or dset.shape[0] != n:
            _warn_once((h5path, field), f"{h5path}: field '{field}' {dset.shape} {dset.dtype} "
                       "has no XDMF attribute type; left out of the sidecar")
            continue
        attr = ET.SubElement(grid, "Attribute", {
            "Name": field, "AttributeType": atype, "Center": "Node"})
        _data_item(attr, f"{rel}:/{GROUP}/{name}/{field}", dset.shape, dset.dtype)
    return grid


def write_xdmf(h5path, xdmf_path=None, cache=None):
    """Write the XDMF sidecar of ``h5path`` (default: same name, ``.xdmf``); returns its path.

    The file is replaced atomically, so a viewer never sees a half-written sidecar.
    ``cache``: see :func:`build_xdmf`.
    """
    xdmf_path = os.path.abspath(xdmf_path or xdmf_path_for(h5path))
    tree = build_xdmf(h5path, xdmf_path, cache)
    ET.indent(tree, space="  ")
    tmp = f"{xdmf_path}.tmp{os.getpid()}"
    with open(tmp, "wb") as out:
        out.write(b'<?xml version="1.0" encoding="utf-8"?>\n')
        tree.write(out, encoding="utf-8", xml_declaration=False)
        out.write(b"\n")
    os.replace(tmp, xdmf_path)
    return xdmf_path


def rebuild_xdmf_main(argv=None):
    """CLI: ``python -m pmpmsph xdmf RUN.h5|RUN [-o RUN.xdmf]``; returns the exit status."""
    parser = argparse.ArgumentParser(
        prog="pmpmsph xdmf",
        description="(Re)build the XDMF sidecar of pmpmsph snapshot files for ParaView.")
    parser.add_argument("h5", nargs="+", help="snapshot file(s) written by a run, or run "
                        "folder(s) (their particles.h5)")
    parser.add_argument("-o", "--output", help="XDMF path (one input only; default RUN.xdmf)")
    args = parser.parse_args(argv)
    if args.output and len(args.h5) > 1:
        parser.error("--output needs exactly one input file")
    status = 0
    for h5 in args.h5:
        if os.path.isdir(h5):
            h5 = os.path.join(h5, "particles.h5")
        try:
            out = write_xdmf(h5, args.output)
        except (OSError, ValueError) as exc:
            print(f"pmpmsph xdmf: {h5}: {exc}", file=sys.stderr)
            status = 2
            continue
        print(out)
    return status
