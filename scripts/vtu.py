"""Reading the ParaView files FreeFEM's iovtk writes (inline base64 "binary": a 4-byte length
header, then the data) into numpy arrays, for the report's figures."""

import base64
import re

import numpy as np

DTYPES = {"Float32": "<f4", "Float64": "<f8", "Int32": "<i4", "UInt8": "u1"}


def read_vtu(path):
    """Returns points (n x 3), cells (list of node-index arrays), cell types, and the named
    point and cell arrays (dict name -> array, shaped (n, components) when components > 1)."""
    text = open(path).read()
    out = {}
    section = None
    for match in re.finditer(r"<(PointData|CellData|Points|Cells)\b|<DataArray([^>]*)>\s*(.*?)\s*</DataArray>", text, re.S):
        if match.group(1):
            section = match.group(1)
            continue
        attrs, data = match.group(2), match.group(3)
        kind = re.search(r'type="(\w+)"', attrs).group(1)
        name = re.search(r'Name="(\w+)"', attrs)
        comps = re.search(r'NumberOfComponents="(\d+)"', attrs)
        raw = base64.b64decode(data.strip())
        values = np.frombuffer(raw[4:4 + int(np.frombuffer(raw[:4], "<u4")[0])], DTYPES[kind])
        if comps and int(comps.group(1)) > 1:
            values = values.reshape(-1, int(comps.group(1)))
        out[(section, name.group(1) if name else "points")] = values
    points = out[("Points", "points")].astype(float)
    offsets = out[("Cells", "offsets")]
    connectivity = out[("Cells", "connectivity")]
    starts = np.concatenate([[0], offsets[:-1]])
    cells = [connectivity[s:e] for s, e in zip(starts, offsets)]
    point_data = {k[1]: v for k, v in out.items() if k[0] == "PointData"}
    cell_data = {k[1]: v for k, v in out.items() if k[0] == "CellData"}
    return points, cells, out[("Cells", "types")], point_data, cell_data


def triangles_2d(path):
    """2D meshes: node coordinates, displacement (n x 2), triangles (m x 3), von Mises per triangle."""
    points, cells, types, pdata, cdata = read_vtu(path)
    keep = [i for i, t in enumerate(types) if t == 5]
    tris = np.array([cells[i] for i in keep])
    return points[:, :2], pdata["displacement"][:, :2], tris, cdata["von_Mises"][keep]


def slice_3d(path, axis=1, value=0.0):
    """3D meshes: the faces of tetrahedra lying on the plane x[axis] = value (a symmetry
    plane), as a 2D triangulation of the two other coordinates, with the tetrahedra's von Mises."""
    points, cells, types, pdata, cdata = read_vtu(path)
    on_plane = np.abs(points[:, axis] - value) < 1e-9 * max(1.0, np.abs(points).max())
    other = [a for a in range(3) if a != axis]
    faces, vm = [], []
    for i, t in enumerate(types):
        if t != 10:
            continue
        nodes = [n for n in cells[i] if on_plane[n]]
        if len(nodes) == 3:
            faces.append(nodes)
            vm.append(cdata["von_Mises"][i])
    return points[:, other], pdata["displacement"][:, other], np.array(faces), np.array(vm)
