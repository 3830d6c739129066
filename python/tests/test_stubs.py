# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""The stubs (strata.pyi) and the module agree: every public name of one is in
the other, and help() shows docstrings."""

import ast
import pathlib
import pydoc

import strata

STUBS = pathlib.Path(strata.__file__).with_name("strata.pyi")


def stub_names():
    tree = ast.parse(STUBS.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = {n.name if isinstance(n, ast.FunctionDef) else n.target.id
                                for n in node.body if isinstance(n, (ast.FunctionDef, ast.AnnAssign))}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
    return names


def test_stubs_sit_beside_the_module():
    assert STUBS.exists(), f"{STUBS} is missing"


def test_stubs_and_module_name_the_same_things():
    stubs = stub_names()
    public = {n for n in dir(strata) if not n.startswith("_")}
    assert set(stubs) <= public, f"in the stubs only: {set(stubs) - public}"
    assert public - set(stubs) == set(), f"not in the stubs: {public - set(stubs)}"
    for name, members in stubs.items():
        if members is None:
            continue
        cls = getattr(strata, name)
        real = {n for n in dir(cls) if not n.startswith("_")}
        assert members - {"__init__"} <= real | {"kind", "file", "line", "key", "value"}, name
        if not issubclass(cls, BaseException):
            assert real <= members, f"{name}: not in the stubs: {real - members}"


def test_help_shows_docstrings():
    text = pydoc.render_doc(strata, renderer=pydoc.plaintext)
    for phrase in ("narrow-band level set", "GIL released", "BadInputError"):
        assert phrase in text
