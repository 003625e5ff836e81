"""The committed type stubs are what python/tools/generate_stubs.py writes from the schemas: a model or
parameter added to the library without regenerating them fails here."""

import ast
import inspect
import keyword
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_stubs_match_the_schemas(tmp_path):
    out = tmp_path / "stub.pyi"
    subprocess.run([sys.executable, str(ROOT / "python" / "tools" / "generate_stubs.py"), str(out)],
                   check=True, env=dict(os.environ))
    committed = (ROOT / "python" / "pyskylight" / "__init__.pyi").read_text()
    assert out.read_text() == committed, (
        "python/pyskylight/__init__.pyi is stale: regenerate it with "
        "`PYTHONPATH=build/python /usr/bin/python3 python/tools/generate_stubs.py`")
    tree = ast.parse(committed)
    sky = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Sky")
    inits = [f for f in sky.body if isinstance(f, ast.FunctionDef) and f.name == "__init__"]
    import pyskylight
    assert len(inits) == len(pyskylight.models())
    # Every model's own parameters are keywords of its overload.
    for m, f in zip(pyskylight.models(), inits):
        names = {a.arg for a in f.args.kwonlyargs}
        for p in m["parameters"]:
            assert p["name"].replace("-", "_") in names, (m["name"], p["name"])
    # Every operation has a run() overload with its parameters as keywords.
    runs = [f for f in tree.body if isinstance(f, ast.FunctionDef) and f.name == "run"]
    assert len(runs) == len(pyskylight.operations())
    for op, f in zip(pyskylight.operations(), runs):
        assert ast.literal_eval(f.args.args[0].annotation.slice) == op["name"]
        names = {a.arg for a in f.args.kwonlyargs}
        spelled = {p["name"].replace("-", "_") for p in op["parameters"]}
        assert {n + "_" if keyword.iskeyword(n) else n for n in spelled} == names, op["name"]
        assert (f.args.kwarg is not None) == op["model_parameters"], op["name"]
    # Every public method of Sky is in the stub with the class's parameter names, in order.
    stubbed = {f.name: f for f in sky.body if isinstance(f, ast.FunctionDef)}
    for name, fn in inspect.getmembers(pyskylight.Sky, inspect.isfunction):
        if name.startswith("_"):
            continue
        assert name in stubbed, f"Sky.{name} is missing from the stubs"
        a = stubbed[name].args
        stub_names = [x.arg for x in a.args + a.kwonlyargs] + ([a.kwarg.arg] if a.kwarg else [])
        assert stub_names == list(inspect.signature(fn).parameters), name


def test_submodule_stubs_list_every_public_function_with_its_parameters():
    import importlib
    import pyskylight
    for name in ("distributed", "estimate", "haze", "io", "nn", "sh"):
        module = importlib.import_module(f"pyskylight.{name}")
        tree = ast.parse((ROOT / "python" / "pyskylight" / f"{name}.pyi").read_text())
        stubbed = {n.name: n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        for fname, fn in vars(module).items():
            if fname.startswith("_") or getattr(fn, "__module__", None) != module.__name__:
                continue
            assert fname in stubbed, f"pyskylight.{name}.{fname} is missing from {name}.pyi"
            if inspect.isfunction(fn):
                a = stubbed[fname].args
                names = [x.arg for x in a.args + a.kwonlyargs] + ([a.kwarg.arg] if a.kwarg else [])
                assert names == list(inspect.signature(fn).parameters), f"{name}.{fname}"
