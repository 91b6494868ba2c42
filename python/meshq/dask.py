"""Jobs larger than one machine, on a ``dask.distributed`` cluster.

Two jobs scale: baking a directory of meshes into blobs, and answering ray, closest-point and
signed-distance batches over many blobs. Blobs go to workers as bytes once — sent from this
process inside the task that decodes them, or read by the workers from storage they share —
and are decoded there (validated, never rebuilt) into :class:`meshq.Mesh` objects that stay
in the workers' memory for every later query. Results come back in input order and equal the
single-process answers bit for bit (the core's answers do not depend on the machine or the
thread count); large results can come back through shared storage instead of the cluster's
connections (``out=``).

A worker lost in the middle of a job loses nothing: what it held is made again from the
bytes the scheduler keeps in each blob's task or from the files, each task's answer is
returned once, and every file written (a baked blob, a group's answers) appears by atomic
rename, so no half-written file ever carries its name.

Quick start::

    from meshq.dask import Blobs, bake_directory, connect

    client = connect()                                  # a local cluster; or connect("tcp://…")
    paths = bake_directory(client, "meshes/", "blobs/")  # one .meshq blob per mesh file
    blobs = Blobs(client, paths)                        # or Blobs(client, [bytes, …])
    hits = blobs.raycast(origins, directions)           # one (t, triangle, u, v) per blob
    hits = blobs.raycast(origins, directions, out="/dev/shm/hits")  # the same, memory-mapped

Each worker runs one query batch at a time per thread it has; a batch uses the worker's rayon
pool (``RAYON_NUM_THREADS`` sets its size; 1 suits a worker per core).
"""

from __future__ import annotations

import os
import tempfile
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from . import Mesh

BlobSource = bytes | bytearray | memoryview | str | os.PathLike


def _load_group(sources: list) -> list[Mesh]:
    """Decodes each blob of a group: ``bytes``, or the path of a blob file to read."""
    meshes = []
    for source in sources:
        if isinstance(source, bytes):
            meshes.append(Mesh.from_blob(source))
        else:
            with open(source, "rb") as file:
                meshes.append(Mesh.from_blob(file.read()))
    return meshes


def _keep(value: Any) -> Any:
    return value


def _call_group(
    meshes: list[Mesh],
    method: str,
    shared: tuple | None,
    own: list,
    kwargs: dict,
    out: str | None,
    first: int,
) -> Any:
    """``Mesh.<method>`` on each mesh of a group, with the ``shared`` arguments, or each mesh
    with its ``own``: the answers, or with ``out`` a :class:`_Saved` record of the files they
    were written to."""
    if shared is not None:
        answers = [getattr(m, method)(*shared, **kwargs) for m in meshes]
    else:
        answers = [getattr(m, method)(*args, **kwargs) for m, args in zip(meshes, own)]
    if out is None:
        return answers
    return _save_group(answers, out, first)


class _Saved:
    """A group's answers written to files: one ``.npy`` per part of the answer (``t``,
    ``triangle``… for a ray cast), the blobs' arrays one after the other in it."""

    def __init__(self, names: list[str], rows: list[int], single: bool) -> None:
        self.names, self.rows, self.single = names, rows, single

    def load(self) -> list[Any]:
        """Each blob's answer, its arrays views of the memory-mapped files."""
        parts = [np.load(name, mmap_mode="r", allow_pickle=False) for name in self.names]
        answers, start = [], 0
        for count in self.rows:
            arrays = tuple(part[start:start + count] for part in parts)
            answers.append(arrays[0] if self.single else arrays)
            start += count
        return answers


def _save_group(answers: list, out: str, first: int) -> _Saved:
    single = bool(answers) and not isinstance(answers[0], tuple)
    columns = [(a,) if single else a for a in answers]
    for answer in columns:
        for part in answer if isinstance(answer, tuple) else (answer,):
            if not isinstance(part, np.ndarray):
                raise TypeError(f"out= needs a method that returns arrays, got {type(part).__name__}")
    names = []
    for k in range(len(columns[0]) if columns else 0):
        parts = [np.ascontiguousarray(answer[k]) for answer in columns]
        shape = (sum(p.shape[0] for p in parts),) + parts[0].shape[1:]
        header = {"descr": np.lib.format.dtype_to_descr(parts[0].dtype), "fortran_order": False, "shape": shape}
        name = os.path.join(out, f"{first:07}-{k}.npy")
        # Written beside its name and renamed over it: a worker lost mid-write leaves no half
        # file under the name, and the task run again writes the same bytes.
        handle, temporary = tempfile.mkstemp(prefix=".part-", suffix=".npy", dir=out)
        try:
            with os.fdopen(handle, "wb") as file:
                np.lib.format.write_array_header_2_0(file, header)
                for p in parts:
                    file.write(memoryview(p).cast("B"))
            os.replace(temporary, name)
        except BaseException:
            if os.path.exists(temporary):
                os.unlink(temporary)
            raise
        names.append(name)
    return _Saved(names, [answer[0].shape[0] for answer in columns], single)


def _bake_one(source: str, target: str, build: dict, layout: str | None, winding: bool) -> str:
    import trimesh

    loaded = trimesh.load(source, force="mesh", process=False)
    mesh = Mesh(np.asarray(loaded.vertices), np.asarray(loaded.faces), **build)
    blob = mesh.to_blob(layout, winding=winding)
    directory = os.path.dirname(target) or "."
    # Written beside the target and renamed over it: a worker killed mid-write leaves a
    # temporary file, never a half blob under the target's name.
    handle, temporary = tempfile.mkstemp(prefix=".bake-", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(blob)
        os.replace(temporary, target)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise
    return target


def connect(address: str | None = None) -> Any:
    """A ``distributed.Client``: to the scheduler at ``address``, or, without one, to a local
    cluster of one single-threaded worker process per core (each batch then runs on its
    worker's one thread: ``RAYON_NUM_THREADS=1``)."""
    from distributed import Client, LocalCluster

    if address is not None:
        return Client(address)
    cluster = LocalCluster(
        n_workers=os.cpu_count() or 1,
        threads_per_worker=1,
        processes=True,
        env={"RAYON_NUM_THREADS": "1"},
    )
    return Client(cluster)


def _client(client: Any) -> Any:
    """``client`` as given; an address string connected to; ``None``: the client this process
    already has, else a new local cluster's (see :func:`connect`)."""
    if client is None:
        from distributed import get_client

        try:
            return get_client()
        except ValueError:
            return connect()
    if isinstance(client, str):
        return connect(client)
    return client


def bake_directory(
    client: Any,
    source: str | os.PathLike,
    target: str | os.PathLike,
    *,
    pattern: str = "*.obj",
    layout: str | None = None,
    winding: bool = False,
    **build: Any,
) -> list[Path]:
    """Bakes every file in ``source`` matching ``pattern`` (any format trimesh reads; read as
    is, vertices not merged) into ``target/<name>.meshq``, one task per file on ``client``'s
    workers, which must all see both directories. ``build`` takes :class:`meshq.Mesh`'s
    keyword arguments (``structure``, ``quality``…); ``layout`` and ``winding`` are
    ``Mesh.to_blob``'s. ``client``: a ``distributed.Client``, a scheduler address, or
    ``None`` (see :func:`connect`). Returns the blob paths in the sorted order of the sources. A file that
    fails raises its error here, naming the file."""
    client = _client(client)
    sources = sorted(Path(source).glob(pattern))
    out = Path(target)
    out.mkdir(parents=True, exist_ok=True)
    targets = [str(out / (s.stem + ".meshq")) for s in sources]
    futures = [
        client.submit(_bake_one, str(s), t, build, layout, winding, pure=False, key=f"meshq-bake-{i}-{s.name}")
        for i, (s, t) in enumerate(zip(sources, targets))
    ]
    done = []
    for s, future in zip(sources, futures):
        try:
            done.append(Path(future.result()))
        except Exception as error:
            raise RuntimeError(f"baking {s} failed: {error}") from error
    return done


def _byte_size(source: bytes | str) -> int:
    return len(source) if isinstance(source, bytes) else os.path.getsize(source)


def _even_bounds(sizes: list[int], count: int) -> list[int]:
    """Where ``count`` runs of consecutive items, each about as large in total as the next,
    begin: ``[0, …, len(sizes)]``, every run holding at least one item (fewer runs than
    ``count`` when there are fewer items)."""
    total, bounds, running = sum(sizes), [0], 0
    for i, size in enumerate(sizes[:-1]):
        running += size
        runs_left = count - len(bounds)
        # A run ends once it reaches its share, or where the items left are just enough for
        # one run each.
        if runs_left > 0 and (running * count >= total * len(bounds) or len(sizes) - 1 - i <= runs_left):
            bounds.append(i + 1)
    return bounds + [len(sizes)] if sizes else [0]


class Blobs:
    """Blobs placed on a cluster once and queried many times.

    ``blobs``: ``bytes`` (sent once, inside the task that decodes them, so the scheduler can run
    that task again if its worker is lost) or paths of blob files every worker can read (read
    by the workers, and read again if a worker is lost). Each blob is decoded once on a worker
    into a :class:`meshq.Mesh` that stays in that worker's memory.

    ``client``: a ``distributed.Client``, a scheduler address, or ``None`` (the client this
    process has, else a local cluster: see :func:`connect`).

    Blobs travel and are queried in groups, one task per group, so that a thousand small blobs
    cost the scheduler a few dozen tasks, not thousands: by default as many groups for every
    worker thread, at least four, and about 32 blobs a group at most, each group holding about as many bytes of
    blob as the next (the work a query costs grows with them); ``group`` gives a fixed number
    of blobs per group instead. Groups are dealt to the workers' threads in turn, so each
    thread gets about the same work (a group moves elsewhere only when its worker is lost).
    """

    def __init__(self, client: Any, blobs: Sequence[BlobSource], *, group: int | None = None) -> None:
        self.client = client = _client(client)
        sources: list[bytes | str] = []
        for i, blob in enumerate(blobs):
            if isinstance(blob, (bytes, bytearray, memoryview)):
                sources.append(bytes(blob))
            else:
                path = os.fspath(blob)
                if not os.path.isfile(path):
                    raise FileNotFoundError(f"blobs[{i}]: no such file: {path}")
                sources.append(path)
        threads = client.nthreads()
        if group is None:
            # At least four groups per worker thread, as many for each (for balance), and
            # about 32 blobs in a group at most, so answers stream back while other groups
            # still run.
            slots = max(1, sum(threads.values()))
            count = max(4, -(-len(sources) // (32 * slots))) * slots
            bounds = _even_bounds([_byte_size(s) for s in sources], count)
        elif group < 1:
            raise ValueError(f"group must be at least 1, got {group}")
        else:
            bounds = list(range(0, len(sources), group)) + [len(sources)]
        # One slot per worker thread, the groups dealt to them in turn.
        slots = [address for address, n in sorted(threads.items()) for _ in range(n)]
        self._count = len(sources)
        self._sizes = []
        self._groups = []
        for i, (start, stop) in enumerate(zip(bounds, bounds[1:])):
            part = sources[start:stop]
            place = {"workers": [slots[i % len(slots)]], "allow_other_workers": True} if slots else {}
            with warnings.catch_warnings():
                # Blobs are meant to travel in their task; Dask warns about large tasks.
                warnings.simplefilter("ignore", UserWarning)
                self._groups.append(client.submit(_load_group, part, pure=False, **place))
            self._sizes.append(len(part))

    def __len__(self) -> int:
        return self._count

    def _shared(self, value: Any) -> Any:
        # An argument every task reads is the result of one task holding it: workers fetch it
        # from each other, and the scheduler can run that task again if its holders are lost
        # (scattered data could not be recovered).
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            return self.client.submit(_keep, value, pure=False)

    def submit(
        self,
        method: str,
        *args: Any,
        per_blob: bool = False,
        out: str | os.PathLike | None = None,
        **kwargs: Any,
    ) -> list[Any]:
        """Starts ``Mesh.<method>(*args, **kwargs)`` on every blob and returns one future per
        group; :meth:`gather` turns them into the answers in blob order. The arguments go to
        the cluster once; with ``per_blob=True`` each positional argument is instead a sequence
        holding one value per blob.

        ``out``: a directory the workers and this process share (made if missing). Each
        group's answers are then written there as ``.npy`` files, one per part of the answer
        (``<first blob>-<part>.npy``, the group's blobs one after the other), and
        :meth:`gather` returns views of them memory-mapped, so results pass through storage (on one
        machine, the page cache: a file system in memory such as ``/dev/shm`` makes that a
        copy in memory) instead of the cluster's connections. Only for methods that return
        arrays."""
        if out is not None:
            out = os.fspath(out)
            os.makedirs(out, exist_ok=True)
        starts = [sum(self._sizes[:i]) for i in range(len(self._sizes))]
        futures = []
        if per_blob:
            for a in args:
                if len(a) != self._count:
                    raise ValueError(
                        f"per_blob arguments need one value per blob ({self._count}), got {len(a)}"
                    )
            for meshes, size, start in zip(self._groups, self._sizes, starts):
                own = [tuple(a[i] for a in args) for i in range(start, start + size)]
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", UserWarning)
                    futures.append(
                        self.client.submit(
                            _call_group, meshes, method, None, own, kwargs, out, start, pure=False
                        )
                    )
            return futures
        shared = self._shared(args)
        return [
            self.client.submit(_call_group, meshes, method, shared, [], kwargs, out, start, pure=False)
            for meshes, start in zip(self._groups, starts)
        ]

    def gather(self, futures: list[Any]) -> list[Any]:
        """The answers of :meth:`submit`'s futures, in blob order (memory-mapped arrays when
        it was given ``out``). Each group's answers are fetched as soon as they are ready,
        while the others still run."""
        return self._collect(futures, release=False)

    @staticmethod
    def _collect(futures: list[Any], release: bool) -> list[Any]:
        from distributed import as_completed

        parts: list[Any] = [None] * len(futures)
        place = {future.key: i for i, future in enumerate(futures)}
        for future, answers in as_completed(futures, with_results=True):
            parts[place[future.key]] = answers.load() if isinstance(answers, _Saved) else answers
            if release:
                # The worker may free the group's answers now, and reuse that memory for the
                # groups still running rather than take fresh pages from the system.
                future.release()
        return [answer for part in parts for answer in part]

    def map(
        self,
        method: str,
        *args: Any,
        per_blob: bool = False,
        out: str | os.PathLike | None = None,
        **kwargs: Any,
    ) -> list[Any]:
        """:meth:`submit`, then :meth:`gather`: the answers in blob order. Each group's answers
        leave the cluster's memory as soon as they are here."""
        futures = self.submit(method, *args, per_blob=per_blob, out=out, **kwargs)
        return self._collect(futures, release=True)

    def raycast(self, origins: Any, directions: Any, **options: Any) -> list[tuple]:
        """``Mesh.raycast`` of the same rays on every blob: one ``(t, triangle, u, v)`` per
        blob, in blob order (``out`` as for :meth:`submit`)."""
        return self.map(
            "raycast", np.asarray(origins, np.float32), np.asarray(directions, np.float32), **options
        )

    def closest_points(self, points: Any, **options: Any) -> list[tuple]:
        """``Mesh.closest_points`` of the same points on every blob, in blob order."""
        return self.map("closest_points", np.asarray(points, np.float32), **options)

    def signed_distances(self, points: Any, **options: Any) -> list[tuple]:
        """``Mesh.signed_distances`` of the same points on every blob, in blob order."""
        return self.map("signed_distances", np.asarray(points, np.float32), **options)
