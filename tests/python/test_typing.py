"""The typed surface of `import arbor`: signatures, docs and the stub made from the run option descriptors,
a namespace that holds the API only, result fields that dir() shows, and misspelt keywords answered in
Python's terms."""
import ast
import importlib.util
import inspect
import pathlib
import re

import pytest

import arbor

REPO = pathlib.Path(__file__).resolve().parents[2]
STUB = REPO / "python" / "arbor" / "__init__.pyi"


def generator():
    path = REPO / "scripts" / "generate_python_stub.py"
    spec = importlib.util.spec_from_file_location("generate_python_stub", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def scenario():
    return arbor.simulate(world="uniform", landmarks=20, steps=15, seed=2)


def test_the_committed_stub_is_what_the_descriptors_give():
    assert STUB.read_text() == generator().render(STUB.read_text()), \
        "python/arbor/__init__.pyi is stale: run PYTHONPATH=build/python scripts/generate_python_stub.py"


def typed_dict_fields(declared, name):
    """The keys of the stub's TypedDict `name`, its bases' first."""
    node = declared[name]
    inherited = [key for base in node.bases if isinstance(base, ast.Name) and base.id in declared
                 for key in typed_dict_fields(declared, base.id)]
    return inherited + [n.target.id for n in node.body if isinstance(n, ast.AnnAssign)]


def stub_parameters(declared, node):
    """A stub function's parameter names, **options: Unpack[_X] spelt out as _X's keys."""
    names = [a.arg for a in node.args.args + node.args.kwonlyargs]
    kwarg = node.args.kwarg
    if kwarg is not None and isinstance(kwarg.annotation, ast.Subscript) and \
            ast.unparse(kwarg.annotation.value) == "Unpack":
        names += typed_dict_fields(declared, ast.unparse(kwarg.annotation.slice))
    return names


def test_the_stub_declares_the_package_as_it_is():
    """The stub against the package: every public name, and each function's parameters (the run options'
    TypedDicts spelt out). Private names (_Path, the TypedDicts) are the stub's own."""
    tree = ast.parse(STUB.read_text())
    declared = {node.name: node for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    for name in arbor.__all__:
        assert name in declared, f"the stub does not declare arbor.{name}"
    for name, node in declared.items():
        if name.startswith("_"):
            continue
        assert name in arbor.__all__, f"the stub declares {name}, which arbor does not export"
        if isinstance(node, ast.FunctionDef) and inspect.isfunction(getattr(arbor, name)):
            stub = stub_parameters(declared, node)
            runtime = [p.name for p in inspect.signature(getattr(arbor, name)).parameters.values()
                       if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL)]
            assert stub == runtime, name
    init = next(n for n in declared["Filter"].body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
    assert stub_parameters(declared, init) == list(inspect.signature(arbor.Filter.__init__).parameters)
    for cls in ["Filter", "Result", "Scenario"]:
        methods = {n.name for n in declared[cls].body
                   if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")}
        public = {n for n in dir(getattr(arbor, cls)) if not n.startswith("_")}
        assert methods <= public, (cls, methods - public)


def test_run_and_filter_have_the_options_signature_and_docs():
    parameters = inspect.signature(arbor.run).parameters
    assert list(parameters)[0] == "scenario"
    help_text = arbor.cli("run", "--help").stdout
    for option in arbor._options.RUN_KEYWORDS:
        p = parameters[option.keyword]
        assert p.kind == p.KEYWORD_ONLY
        assert f"--{option.name}" in help_text
        assert f"\n{option.keyword} : " in arbor.run.__doc__
        assert option.default is None or isinstance(option.default, option.type), option
    assert parameters["particles"].annotation is int and parameters["chi2"].annotation is float
    assert parameters["relocalize"].default is False
    assert parameters["filter"].annotation.__args__ == tuple(arbor.filters())
    assert parameters["map"].annotation.__args__ == tuple(arbor.map_backends())
    assert "out" not in inspect.signature(arbor.Filter).parameters
    assert "chi2" in inspect.signature(arbor.Filter).parameters


def test_the_namespace_holds_the_api_only():
    """csv, json, np, os and subprocess were public names of the module."""
    public = {name for name in dir(arbor) if not name.startswith("_")}
    assert public == set(arbor.__all__), public ^ set(arbor.__all__)
    assert re.fullmatch(r"\d+(\.\d+)*(\+g[0-9a-f]+(\.dirty)?)?", arbor.__version__), arbor.__version__


def test_result_fields_are_visible_to_dir(scenario):
    result = arbor.run(scenario, assoc="nn", particles=5)
    names = dir(result)
    for field in ["ate_rmse_m", "assoc_f1", "landmarks", "wall_time_s", "trajectory", "to_dir"]:
        assert field in names
    assert set(result.metrics) <= set(names)


def test_a_misspelt_keyword_is_answered_in_python_terms(scenario):
    for call in [lambda **o: arbor.run(scenario, **o), lambda **o: arbor.Filter(scenario, **o)]:
        for wrong, right in [("asoc", "assoc"), ("known_gat", "known_gate"), ("particle", "particles")]:
            with pytest.raises(arbor.InputError, match=re.escape(f"did you mean {right}=?")) as error:
                call(**{wrong: 1})
            assert error.value.field == wrong
            assert "--" not in str(error.value)
