"""The .pyi stubs written from the built module name everything the module has."""

import ast
import builtins
from pathlib import Path

import ssrt


def stub_tree():
    return ast.parse((Path(ssrt.__file__).parent / "_ssrt.pyi").read_text())


def test_stubs_name_every_public_name():
    tree = stub_tree()
    names = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    assert names == set(ssrt.__all__)


def test_stubs_name_only_what_they_define_or_import():
    tree = stub_tree()
    known = set(dir(builtins)) | {"numpy", "os"}
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            known.add(node.name)
        elif isinstance(node, ast.ImportFrom):
            known.update(a.asname or a.name for a in node.names)
    annotations = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.AnnAssign, ast.arg)) and node.annotation is not None:
            annotations.append(node.annotation)
        elif isinstance(node, ast.FunctionDef) and node.returns is not None:
            annotations.append(node.returns)
    used = {n.id for a in annotations for n in ast.walk(a) if isinstance(n, ast.Name)}
    assert {"Optional", "RenderSettings", "Frame"} <= used
    assert used <= known, used - known


def test_settings_stub_has_every_field_as_a_keyword():
    settings = next(n for n in stub_tree().body
                    if isinstance(n, ast.ClassDef) and n.name == "RenderSettings")
    init = next(n for n in settings.body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
    keywords = {a.arg: ast.unparse(a.annotation) for a in init.args.kwonlyargs}
    for f in ssrt.RenderSettings.fields():
        assert keywords[f["name"]] == f["type"], f["name"]
