"""Writes the ssrt package's type stubs (_ssrt.pyi) from the built extension module.

pybind11 puts each function's signature in the first line of its docstring
("render(self: ssrt._ssrt.Renderer, scene: ssrt._ssrt.Scene, ...) -> ssrt._ssrt.Frame");
this turns those lines into stub declarations, and RenderSettings' constructor into explicit
keyword arguments from its field table (RenderSettings.fields()), so the stubs hold nothing
the module does not say. Run by the build after the module links.

Usage: gen_stubs.py PACKAGE_DIR  (the folder holding _ssrt*.so, on PYTHONPATH's package ssrt)
"""

import inspect
import re
import sys
from pathlib import Path

import ssrt._ssrt as ext

PREFIX = "ssrt._ssrt."


def clean(text):
    """Module-qualified names as the stub sees them; numpy's array spelled as numpy has it."""
    text = text.replace(PREFIX, "")
    text = re.sub(r"numpy\.ndarray\[[^\]]*\]", "numpy.ndarray", text)
    # The binding takes paths as a handle and checks them itself (python/files.cpp pathText).
    text = re.sub(r": handle\b", ": str | os.PathLike[str]", text)
    text = re.sub(r"[Ll]ist\[(\w+)\[3\]\]", r"tuple[\1, \1, \1]", text)  # std::array<T, 3>
    text = re.sub(r"ssrt::python::Py(\w+)", r"\1", text)  # a class bound after its first use
    return text.replace("Dict[", "dict[").replace("List[", "list[").replace("Tuple[", "tuple[")


def signature(doc, name, required=True):
    """The first signature line of a pybind11 docstring, as 'name(args) -> ret'."""
    for line in (doc or "").splitlines():
        line = line.strip()
        if line.startswith(name + "("):
            return clean(line)
    if required:
        raise SystemExit(f"gen_stubs: no signature for {name} in its docstring")
    return None


def defaults_to_ellipsis(sig):
    """Default values as '...' (their reprs are not always valid Python)."""
    head, _, ret = sig.rpartition(" -> ")
    name, _, args = head.partition("(")
    args = args[:-1]
    parts, depth, cur = [], 0, ""
    for ch in args:
        if ch in "[(":
            depth += 1
        elif ch in "])":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        parts.append(cur.strip())
    parts = [re.sub(r"=.*$", "= ...", p) for p in parts]
    return f"{name}({', '.join(parts)}) -> {ret}"


def function_stub(func, name, indent=""):
    sig = defaults_to_ellipsis(signature(func.__doc__, name))
    return f"{indent}def {sig}: ...\n"


def settings_init():
    args = ["self", "*", "quality: str = ...", "isa: str = ..."]
    args += [f"{f['name']}: {f['type']} = ..." for f in ext.RenderSettings.fields()]
    return "    def __init__(" + ", ".join(args) + ") -> None: ...\n"


def class_stub(cls):
    field_types = {f["name"]: f["type"] for f in ext.RenderSettings.fields()}
    field_types["isa"] = "str"
    out = [f"class {cls.__name__}:\n"]
    for name, member in sorted(vars(cls).items()):
        if name.startswith("_") and name not in ("__init__", "__getitem__", "__contains__",
                                                 "__iter__", "__next__", "__len__"):
            continue
        if cls is ext.RenderSettings and name == "__init__":
            out.append(settings_init())
        elif name == "__init__" and not signature(member.__doc__, name, required=False):
            continue  # no constructor: made by the module only
        elif isinstance(member, property) and cls is ext.RenderSettings and name in field_types:
            out.append(f"    {name}: {field_types[name]}\n")
        elif isinstance(member, property):
            getter = signature(member.fget.__doc__, "")
            kind = getter.rpartition(" -> ")[2]
            out.append(f"    {name}: {kind}\n")
        elif isinstance(member, staticmethod) or type(member).__name__ == "builtin_function_or_method":
            out.append("    @staticmethod\n" + function_stub(getattr(cls, name), name, "    "))
        elif callable(member):
            out.append(function_stub(member, name, "    "))
    return "".join(out) + "\n"


def main():
    package = Path(sys.argv[1])
    out = ["# Written by python/gen_stubs.py from the built module: do not edit.\n",
           "import os\nfrom typing import Optional\n\nimport numpy\n\n"]
    for name, obj in sorted(vars(ext).items()):
        if name.startswith("_"):
            continue
        if inspect.isclass(obj):
            out.append(class_stub(obj))
        elif callable(obj):
            out.append(function_stub(obj, name))
    (package / "_ssrt.pyi").write_text("".join(out))
    (package / "__init__.pyi").write_text(
        "# Written by python/gen_stubs.py: the package re-exports its extension.\n"
        "from ssrt._ssrt import *\n")


if __name__ == "__main__":
    main()
