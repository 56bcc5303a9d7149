"""The type stubs (lantern/__init__.pyi) against the module: every public name of the package
and of its classes has a stub, each stub of an extension function or method takes the
parameters the module's own signature names, in order, and every public function has a
docstring (what help() shows)."""
import ast
import inspect
import pathlib
import re

import pytest


@pytest.fixture(scope="module")
def stubs(lantern_module):
    path = pathlib.Path(lantern_module.__file__).with_name("__init__.pyi")
    assert path.exists(), f"{path} is not beside the module"
    assert path.with_name("py.typed").exists(), "py.typed marks the package as typed"
    tree = ast.parse(path.read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef, ast.AnnAssign)):
            name = node.target.id if isinstance(node, ast.AnnAssign) else node.name
            out[name] = node
    return out


def parameters(function):
    args = function.args
    names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
    return [n for n in names if n != "self"]


def module_parameters(obj):
    """The parameter names of a pybind11 function from its signature line, or inspect's."""
    doc = (obj.__doc__ or "").strip().split("\n")[0]
    match = re.match(r"\w+\((.*)\) ->", doc)
    if not match:
        return [p for p in inspect.signature(obj).parameters if p not in ("self",)]
    names = re.findall(r"(?:^|, )\*?(\w+)(?=:)", match.group(1))
    return [n for n in names if n != "self"]


def test_every_public_name_has_a_stub(lantern_module, stubs):
    for name in lantern_module.__all__:
        assert name in stubs, f"lantern.{name} has no stub"
    for cls in ("Renderer", "Scene"):
        members = {n: m for n, m in stubs[cls].body and [(s.name, s) for s in stubs[cls].body
                                                            if isinstance(s, ast.FunctionDef)]}
        for name in dir(getattr(lantern_module, cls)):
            if not name.startswith("_"):
                assert name in members, f"lantern.{cls}.{name} has no stub"


def test_stubs_take_the_modules_parameters(lantern_module, stubs):
    checked = 0
    for name in ("load", "write_image", "list_devices", "builtin_scenes", "build_info"):
        assert parameters(stubs[name]) == module_parameters(getattr(lantern_module, name)), name
        checked += 1
    for cls in ("Renderer", "Scene"):
        for s in stubs[cls].body:
            if not isinstance(s, ast.FunctionDef) or s.name.startswith("_") or s.name == "frames":
                continue
            if any(isinstance(d, ast.Name) and d.id == "property" for d in s.decorator_list):
                continue
            member = getattr(getattr(lantern_module, cls), s.name)
            assert parameters(s) == module_parameters(member), f"{cls}.{s.name}"
            checked += 1
    assert checked >= 12


def test_every_public_function_has_a_docstring(lantern_module):
    for name in lantern_module.__all__:
        obj = getattr(lantern_module, name)
        if callable(obj):
            assert (obj.__doc__ or "").strip(), f"lantern.{name} has no docstring"
    for cls in (lantern_module.Renderer, lantern_module.Scene, lantern_module.Pool):
        for name, member in vars(cls).items():
            if not name.startswith("_") and callable(member):
                assert (member.__doc__ or "").strip(), f"{cls.__name__}.{name} has no docstring"
