"""Mesh files as the benchmark scripts read and write them: OBJ in (fan-triangulated, in file
order, as the meshq command reads it) and binary little-endian PLY with float32 positions and
uint32 triangle lists (what `meshq remesh` writes) in and out."""
import pathlib

import numpy as np

PLY_FACE = np.dtype([("n", "u1"), ("i", "<u4", 3)])


def read_obj(path, dtype=np.float64):
    """Positions and fan-triangulated faces, in file order."""
    v, f = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            v.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            idx = [int(x.split("/")[0]) - 1 for x in parts[1:]]
            f.extend([idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1))
    return np.array(v, dtype=dtype), np.array(f, dtype=np.int64)


def read_ply(path, dtype=np.float64):
    """A binary PLY of float32 x, y, z and uchar-counted uint32 triangle lists."""
    data = pathlib.Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("latin1")
    nv = int(header.split("element vertex ")[1].split()[0])
    nf = int(header.split("element face ")[1].split()[0])
    v = np.frombuffer(data, dtype="<f4", count=3 * nv, offset=end).reshape(nv, 3)
    faces = np.frombuffer(data, dtype=PLY_FACE, count=nf, offset=end + 12 * nv)
    return v.astype(dtype), faces["i"].astype(np.int64)


def write_ply(path, v, f):
    """The PLY `read_ply` reads."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(v)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(f)}\nproperty list uchar uint vertex_indices\nend_header\n"
    )
    faces = np.zeros(len(f), dtype=PLY_FACE)
    faces["n"] = 3
    faces["i"] = f
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(np.ascontiguousarray(v, dtype="<f4").tobytes())
        out.write(faces.tobytes())


def read_mesh(path, dtype=np.float64):
    """An OBJ or a PLY, by extension."""
    path = pathlib.Path(path)
    return read_ply(path, dtype) if path.suffix == ".ply" else read_obj(path, dtype)
