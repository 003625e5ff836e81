"""The committed type stubs are what python/tools/generate_stubs.py writes from the schemas: a model or
parameter added to the library without regenerating them fails here."""

import ast
import inspect
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_stubs_match_the_schemas(tmp_path):
    out = tmp_path / "stub.pyi"
    subprocess.run([sys.executable, str(ROOT / "python" / "tools" / "generate_stubs.py"), str(out)],
                   check=True, env=dict(os.environ))
    committed = (ROOT / "python" / "skylight" / "__init__.pyi").read_text()
    assert out.read_text() == committed, (
        "python/skylight/__init__.pyi is stale: regenerate it with "
        "`PYTHONPATH=build/python /usr/bin/python3 python/tools/generate_stubs.py`")
    tree = ast.parse(committed)
    sky = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Sky")
    inits = [f for f in sky.body if isinstance(f, ast.FunctionDef) and f.name == "__init__"]
    import skylight
    assert len(inits) == len(skylight.models())
    # Every model's own parameters are keywords of its overload.
    for m, f in zip(skylight.models(), inits):
        names = {a.arg for a in f.args.kwonlyargs}
        for p in m["parameters"]:
            assert p["name"].replace("-", "_") in names, (m["name"], p["name"])
    # Every public method of Sky is in the stub with the class's parameter names, in order.
    stubbed = {f.name: f for f in sky.body if isinstance(f, ast.FunctionDef)}
    for name, fn in inspect.getmembers(skylight.Sky, inspect.isfunction):
        if name.startswith("_"):
            continue
        assert name in stubbed, f"Sky.{name} is missing from the stubs"
        a = stubbed[name].args
        stub_names = [x.arg for x in a.args + a.kwonlyargs] + ([a.kwarg.arg] if a.kwarg else [])
        assert stub_names == list(inspect.signature(fn).parameters), name


def test_submodule_stubs_list_every_public_function_with_its_parameters():
    import importlib
    import skylight
    for name in ("estimate", "haze", "io", "nn", "sh"):
        module = importlib.import_module(f"skylight.{name}")
        tree = ast.parse((ROOT / "python" / "skylight" / f"{name}.pyi").read_text())
        stubbed = {n.name: n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        for fname, fn in vars(module).items():
            if fname.startswith("_") or getattr(fn, "__module__", None) != module.__name__:
                continue
            assert fname in stubbed, f"skylight.{name}.{fname} is missing from {name}.pyi"
            if inspect.isfunction(fn):
                a = stubbed[fname].args
                names = [x.arg for x in a.args + a.kwonlyargs] + ([a.kwarg.arg] if a.kwarg else [])
                assert names == list(inspect.signature(fn).parameters), f"{name}.{fname}"
