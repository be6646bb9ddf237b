"""The shape of the package: its layers (pyproject.toml's import-linter contract: each
layer imports only those below it, imports inside functions included), no import cycle
between modules, no package reaching into another's private modules or names, and the
core and the solvers (the contract, the driver, simulate, crosscheck, sensitivities, the
backend registry, the integrators and generic backends) name no concrete model; a model
declares what it needs (its default backend, engines, DAE form, derivatives)."""

import ast
import pathlib

import blockdae as bd

PACKAGE = pathlib.Path(bd.__file__).resolve().parent
CORE = ["core", "solvers", "backends.py"]
MODELS = ("SlidingBlock", "PlanarBlock", "SpringSupportedMass", "FlexibleSlidingMass", "RockingBlock")


def _modules():
    """Module name -> path, for every module of the package."""
    modules = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return modules


def import_graph():
    """Module -> the package's modules it imports, at module level or inside functions
    (``from .x import y`` names the submodule x.y where there is one, else x)."""
    modules = _modules()
    graph = {}
    for name, path in modules.items():
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        targets = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level:
                module = node.module.split(".") if node.module else []
                base = ".".join(package[:len(package) - node.level + 1] + module)
                targets |= {f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base for a in node.names}
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("blockdae"):
                targets.add(node.module)
            elif isinstance(node, ast.Import):
                targets |= {a.name for a in node.names if a.name.startswith("blockdae")}
        graph[name] = targets & set(modules)
    return graph


def cycles(graph):
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while not component or component[-1] != v:
                component.append(stack.pop())
                on_stack.discard(component[-1])
            if len(component) > 1:
                found.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return found


def test_the_cycle_finder_finds_a_cycle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_no_import_cycle():
    assert cycles(import_graph()) == []


def _names(path):
    """The identifiers a module uses or imports."""
    tree = ast.parse(path.read_text())
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    return names | {a.asname or a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) for a in n.names}


def test_the_core_names_no_concrete_model():
    for entry in CORE:
        paths = sorted((PACKAGE / entry).rglob("*.py")) if (PACKAGE / entry).is_dir() else [PACKAGE / entry]
        for path in paths:
            assert not _names(path) & set(MODELS), (path.name, _names(path) & set(MODELS))


def test_studies_name_no_model_but_their_default_block():
    """bd.study sweeps what a model declares (study_parameter, study_batch) or, by default,
    the keyword it is given: it names only the 1-D block, its default."""
    for path in sorted((PACKAGE / "studies").rglob("*.py")):
        assert not _names(path) & (set(MODELS) - {"SlidingBlock"}), path.name


#: the contract's classes a model subclasses (blockdae.core.contract)
CONTRACT = {"AbstractHybridModel", "BatchedModel", "DifferentiableModel", "LinearModesModel", "EngineModel",
            "StudyModel"}
#: the front ends, which build the models a user names (a command, a page), and the top
#: level, which exports them
FRONT_ENDS = ("cli", "app", "__init__.py")
#: (module, model) named outside the model's package on purpose, each with its reason
NAMED_ON_PURPOSE = {
    ("studies/_study.py", "SlidingBlock"): "bd.study's default block",
    ("design/_models.py", "PlanarBlock"): "design.Planar, the block on a plane's design model",
    ("design/_models.py", "FlexibleSlidingMass"): "design.Flexible's dD/dp, through the flexible mass's JAX twin",
    ("planar/_elms.py", "SlidingBlock"): "Elms's set-up: the 1-D block a plane's slide reduces to",
}


def built_in_models() -> dict:
    """Class name -> its package, of every model defined in the package (a class whose bases
    name a class of the contract), found in the source."""
    found = {}
    for path in PACKAGE.rglob("*.py"):
        package = path.relative_to(PACKAGE).parts[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if package != "core" and isinstance(node, ast.ClassDef) \
                    and {ast.unparse(base).split(".")[-1] for base in node.bases} & CONTRACT:
                found[node.name] = package
    return found


def names_outside(module: str, source: str, models: dict) -> set:
    """The models of ``models`` (class name -> its package) that ``source``, the module at
    ``module`` (a path relative to the package), names in code (uses, imports or reads as an
    attribute, ``bd.RockingBlock``; docstrings and messages aside) outside their packages;
    none in the front ends."""
    parts = pathlib.PurePosixPath(module).parts
    if parts[0] in FRONT_ENDS:
        return set()
    tree = ast.parse(source)
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    names |= {n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
    names |= {a.asname or a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) for a in n.names}
    return {model for model in names & set(models) if parts[0] != models[model]}


def test_the_built_in_models_are_found():
    assert set(MODELS) <= set(built_in_models())
    assert built_in_models()["RockingBlock"] == "rocking"


def test_the_check_finds_a_model_named_outside_its_package():
    source, models = "import blockdae as bd\nbd.RockingBlock(b=0.2, h=1.0, mu=0.7)\n", {"RockingBlock": "rocking"}
    assert names_outside("motions/_spectra.py", source, models) == {"RockingBlock"}
    assert names_outside("rocking/_spectra.py", source, models) == set()
    assert names_outside("cli/_rocking.py", source, models) == set()
    assert names_outside("motions/_spectra.py", '"""A bd.RockingBlock in a docstring."""', models) == set()


def test_no_module_outside_a_models_package_names_it():
    """A model declares what the rest needs through the contract: no module outside its
    package names it (the core, solvers, tools and the other models), but the front ends and
    the few named on purpose, each with its reason; a reason that no longer holds fails too."""
    models = built_in_models()
    found = {(path.relative_to(PACKAGE).as_posix(), model) for path in PACKAGE.rglob("*.py")
             for model in names_outside(path.relative_to(PACKAGE).as_posix(), path.read_text(), models)}
    assert found == set(NAMED_ON_PURPOSE)


def test_one_event_shape_and_one_solution_base():
    """Every system's events start with (t, mode_before, mode_after) and every solution
    is an AbstractSolution with t_events, event_table and to_dataframe."""
    import dataclasses

    for event in (bd.sliding.Event, bd.planar.PlanarEvent, bd.upthrow.UpthrowEvent, bd.core.HybridEvent):
        assert issubclass(event, bd.core.AbstractEvent)
        assert [f.name for f in dataclasses.fields(event)][:3] == ["t", "mode_before", "mode_after"]
    for solution in (bd.sliding.Solution, bd.planar.PlanarSolution, bd.upthrow.UpthrowSolution, bd.core.DriverSolution):
        assert issubclass(solution, bd.core.AbstractSolution)
    sol = bd.simulate(bd.SpringSupportedMass(frequency=5.0, damping=0.05), bd.Harmonic(-0.8 * 9.81, 0.2), t_end=0.5)
    assert sol.events[0].kind == "liftoff" and sol.t_events[0] == sol.events[0].t


def test_the_layers_hold():
    """The import-linter contracts of pyproject.toml (imports inside functions count): each
    layer imports only the layers below it; the library never imports the command line."""
    from importlinter.cli import lint_imports

    root = PACKAGE.parent.parent
    assert lint_imports(config_filename=str(root / "pyproject.toml"), no_cache=True, no_logo=True) == 0


def private_imports():
    """Imports of another package's private module or name, as 'module:line: statement'."""
    found = []
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        mine = parts[1] if len(parts) > 2 else None
        for node in ast.walk(ast.parse(path.read_text())):
            if not (isinstance(node, ast.ImportFrom) and node.level):
                continue
            base = list(parts[:-1])[: len(parts) - node.level] + (node.module.split(".") if node.module else [])
            if len(base) < 2 or base[1] == mine:
                continue
            names = [a.name for a in node.names]
            if any(part.startswith("_") for part in base[2:]) or any(n.startswith("_") for n in names):
                found.append(f"{'.'.join(parts)}:{node.lineno}: {ast.unparse(node)}")
    return found


def test_no_package_imports_another_packages_private_names():
    """A package reaches another only through what that package's __init__ exports."""
    assert private_imports() == []
