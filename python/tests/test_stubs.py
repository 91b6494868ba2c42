"""The typed stubs describe the module as it is: the same public names, the same parameters."""

import ast
import inspect
from pathlib import Path

import meshq
from meshq import _meshq

STUB = Path(meshq.__file__).with_name("_meshq.pyi")


def stub_functions():
    tree = ast.parse(STUB.read_text())
    found = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name == "Mesh":
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    found[f"Mesh.{item.name}"] = item
        elif isinstance(node, ast.FunctionDef):
            found[node.name] = node
    return found


def parameters(node):
    a = node.args
    names = [p.arg for p in a.posonlyargs + a.args + a.kwonlyargs]
    return [n for n in names if n not in ("self",)]


def test_every_public_name_has_a_stub_and_back():
    stubs = stub_functions()
    actual = {f"Mesh.{n}" for n in dir(_meshq.Mesh) if not n.startswith("_")}
    actual |= {"Mesh.__init__", "Mesh.__reduce__", "Mesh.__len__"}
    actual |= {n for n in dir(_meshq) if not n.startswith("_") and n != "Mesh"}
    assert actual == set(stubs), (actual ^ set(stubs))


def test_stub_parameters_match_the_signatures():
    stubs = stub_functions()
    for name, node in stubs.items():
        owner, _, attr = name.rpartition(".")
        target = getattr(_meshq.Mesh if owner else _meshq, attr)
        if not callable(target) or attr in ("__reduce__", "__len__", "__init__"):
            continue  # properties, and slots whose signatures Python reports generically
        signature = inspect.signature(target)
        want = [p for p in signature.parameters if p not in ("self", "cls")]
        assert parameters(node) == want, name
    init = inspect.signature(_meshq.Mesh)
    assert parameters(stubs["Mesh.__init__"]) == list(init.parameters)


def test_every_public_call_is_documented():
    for name in dir(_meshq.Mesh):
        if not name.startswith("_"):
            assert (getattr(_meshq.Mesh, name).__doc__ or "").strip(), name
    assert _meshq.remesh.__doc__.strip() and _meshq.Mesh.__doc__.strip()
