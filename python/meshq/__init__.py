"""meshq: ray casts, closest points, inside tests, signed distance and mesh–mesh checks on
triangle meshes, from numpy arrays.

The core is Rust (the same code runs in browsers and on microcontrollers); this package binds
it with numpy arrays in and out. A :class:`Mesh` is built from ``vertices`` / ``faces`` or
loaded from a blob (``bytes`` baked by ``meshq bake``, ``Mesh.to_blob()`` or the JavaScript
package), answers every query the same, bit for bit, on every structure and every machine, and
pickles as its blob, so it travels to Dask workers as bytes (see :mod:`meshq.dask`).

Companion modules: :mod:`meshq.trimesh` (a drop-in for trimesh's ray intersector and
``trimesh.proximity.closest_point``) and :mod:`meshq.dask` (baking and querying many blobs on
a ``dask.distributed`` cluster).
"""

import os as _os

from ._meshq import Mesh, after_fork_in_child as _after_fork_in_child, remesh

# A forked child (multiprocessing's default on Linux) has none of the parent's batch threads:
# from the fork on, batches there run on threads the child makes (see python/src/pool.rs).
_os.register_at_fork(after_in_child=_after_fork_in_child)

__all__ = ["Mesh", "remesh"]
__version__ = "0.1.0"
