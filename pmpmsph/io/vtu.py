"""Snapshots as VTU files (meshio), for tools that do not read XDMF/HDF5.

``python -m pmpmsph vtu RUN [--step N] [--out DIR]`` writes ``DIR/particles_<step>.vtu``
(default DIR = RUN/vtu) for every snapshot of ``RUN/particles.h5`` (or only the one of step
N): the particles as points with one ``vertex`` cell each, every other field as point data
(3x3 tensors as 9 components, row-major), plus ``particles.pvd``, a ParaView collection with
the snapshot times.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

from .snapshot_read import list_snapshots, read_snapshot


def _h5_of(run):
    return run if run.endswith(".h5") else os.path.join(run, "particles.h5")


def snapshot_mesh(data):
    """meshio.Mesh of one snapshot's fields (x of shape (n, 3) required)."""
    import meshio  # noqa: PLC0415 - optional, for .vtu only

    x = np.asarray(data["x"], dtype=np.float64)
    n = len(x)
    point_data = {}
    for name, arr in data.items():
        if name == "x":
            continue
        arr = np.asarray(arr)
        if arr.ndim > 2:
            arr = arr.reshape(n, -1)
        point_data[name] = arr
    return meshio.Mesh(x, [("vertex", np.arange(n, dtype=np.int64).reshape(-1, 1))],
                       point_data=point_data)


def export_vtu(run, out=None, step=None):
    """Write the VTU files; returns their paths. `step`: only the snapshot of that step."""
    import meshio  # noqa: PLC0415 - optional, for .vtu only

    h5 = _h5_of(run)
    infos = list_snapshots(h5)
    if step is not None:
        infos = [i for i in infos if i.step == step]
        if not infos:
            steps = [i.step for i in list_snapshots(h5)]
            raise ValueError(f"{h5} has no snapshot of step {step}; steps: "
                             f"{', '.join(map(str, steps)) or 'none'}")
    out = out or os.path.join(os.path.dirname(os.path.abspath(h5)), "vtu")
    os.makedirs(out, exist_ok=True)
    paths = []
    for info in infos:
        _, _, data = read_snapshot(h5, info.index)
        path = os.path.join(out, f"particles_{info.step:08d}.vtu")
        meshio.write(path, snapshot_mesh(data), file_format="vtu")
        paths.append((info.time, path))
    if step is None:
        root = ET.Element("VTKFile", {"type": "Collection", "version": "0.1"})
        coll = ET.SubElement(root, "Collection")
        for t, path in paths:
            ET.SubElement(coll, "DataSet", {"timestep": repr(t), "part": "0",
                                            "file": os.path.basename(path)})
        ET.indent(root)
        ET.ElementTree(root).write(os.path.join(out, "particles.pvd"), xml_declaration=True,
                                   encoding="utf-8")
    return [p for _, p in paths]


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m pmpmsph vtu",
                                 description="Export the snapshots of a run to VTU (meshio).")
    ap.add_argument("run", help="run folder (or its particles.h5)")
    ap.add_argument("--step", type=int, default=None, help="only the snapshot of this step")
    ap.add_argument("--out", default=None, help="folder for the .vtu files (default RUN/vtu)")
    args = ap.parse_args(argv)
    try:
        paths = export_vtu(args.run, args.out, args.step)
    except (OSError, ValueError, KeyError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"{len(paths)} file(s) in {os.path.dirname(paths[0]) if paths else args.out}")
    return 0
