"""The shape of the project a newcomer reads (issue 35): a short README that states the code's defaults, docs that
describe the project as it is, no private name used across modules, modules of one job each (≤ 1 000 lines), a design
point read by name only where it is made and typed (the config, the Scene and the options).

Each check reads the sources only (no solver runs): fast.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
SOURCES = sorted((ROOT / "study").rglob("*.py"))

#: Modules allowed over :data:`MAX_LINES` lines, each with its reason.
LONG_MODULES: set[str] = set()
MAX_LINES = 1000

#: Private names a module may still take from another, each with its reason (issue 35 lists them for later).
PRIVATE_CROSSINGS: set[tuple[str, str]] = set()

#: The one home of Hertz's contact law (its force with the Hunt–Crossley damping, energy, linearised stiffness).
CONTACT_LAW_HOME = "study/physics/contact.py"
#: Modules that still write the law out, each with its reason: the ones left to switch over to the home.
CONTACT_LAW_LEFT: set[str] = set()
#: The law's exponent forms in code (comments and strings left out): ``** 1.5`` / ``** 2.5``, and ``d * sqrt(d)``.
CONTACT_LAW_FORM = re.compile(r"\*\* [12]\.5(?!\d)|\b(\w+) \* (?:\w+ \. )?sqrt \( \1 \)")


#: Where a point's inputs are read by name (``inputs["k"]``, ``inputs.get("k")``): the config, which makes them, and
#: the builders of the typed point from them — the Scene (study/solvers/model/scene.py) and the options
#: (study/solvers/model/options.py); None: the whole module.
INPUT_EDGE: dict[str, set[str] | None] = {
    "study/config.py": None,
    "study/solvers/model/scene.py": {"Scene.from_inputs"},
    "study/solvers/model/options.py": {"study_tolerance", "relative_tolerance", "MethodOptions.from_inputs"},
}
#: The names a point's inputs go by (``study.inputs`` too, a Study's fixed inputs).
INPUT_NAMES = ("inputs", "point")
#: Reads by name left outside the edge: solve_point's method name (the dispatch), the sweep's method axis, and the
#: coverage check's records of two runs of a point (named ``point``, not inputs).
MAX_INPUT_READS = 5


def _qualified_functions(tree: ast.AST) -> dict[ast.AST, str]:
    """Every node of ``tree`` -> the qualified name of the function (or class) it sits in ('' at module level)."""
    where: dict[ast.AST, str] = {}
    stack = [(tree, "")]
    while stack:
        node, name = stack.pop()
        for child in ast.iter_child_nodes(node):
            inner = name
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                inner = f"{name}.{child.name}" if name else child.name
            where[child] = inner
            stack.append((child, inner))
    return where


def _is_inputs(node: ast.AST) -> bool:
    return (isinstance(node, ast.Name) and node.id in INPUT_NAMES
            or isinstance(node, ast.Attribute) and node.attr == "inputs")


def _is_name(key: ast.AST) -> bool:
    return isinstance(key, ast.Constant) and isinstance(key.value, str)


def input_reads(paths=SOURCES, root: Path = ROOT, edge=None) -> list[str]:
    """'file:line (function): code' for every read of a point's inputs by name outside ``edge`` (default
    :data:`INPUT_EDGE`): a subscript ``inputs["k"]`` that is read (not assigned) or a call ``inputs.get("k")``, ``k`` a
    string written out (a loop over every input by a variable, as a point's hash, names none)."""
    edge = INPUT_EDGE if edge is None else edge
    found = []
    for path in paths:
        where = str(path.relative_to(root))
        if where in edge and edge[where] is None:
            continue
        text = path.read_text()
        tree = ast.parse(text)
        functions = _qualified_functions(tree)
        for node in sorted(ast.walk(tree), key=lambda n: (getattr(n, "lineno", 0), getattr(n, "col_offset", 0))):
            read = (isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and _is_inputs(node.value)
                    and _is_name(node.slice)
                    or isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "get"
                    and _is_inputs(node.func.value) and bool(node.args) and _is_name(node.args[0]))
            if read and functions.get(node, "") not in (edge.get(where) or ()):
                found.append(f"{where}:{node.lineno} ({functions.get(node) or 'module'}): "
                             f"{ast.get_source_segment(text, node)}")
    return found


def _module(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_crossings(paths=SOURCES, root: Path = ROOT) -> list[tuple[str, str]]:
    """(importing file, 'module._name') for every private name of a study module used by another module: imported
    (``from study.x import _y``) or read as an attribute of an imported module (``x._y``)."""
    found = []
    for path in paths:
        tree = ast.parse(path.read_text())
        me, modules = _module(path, root), {}
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.startswith("study"):
                        modules[alias.asname or "study"] = alias.name if alias.asname else "study"
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("study"):
                for alias in node.names:
                    if _private(alias.name) and node.module != me:
                        found.append((str(path.relative_to(root)), f"{node.module}.{alias.name}"))
                    modules[alias.asname or alias.name] = f"{node.module}.{alias.name}"
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and _private(node.attr):
                base, chain = node.value, []
                while isinstance(base, ast.Attribute):
                    chain.append(base.attr)
                    base = base.value
                if isinstance(base, ast.Name) and base.id in modules:
                    owner = ".".join([modules[base.id], *reversed(chain)])
                    if owner != me:
                        found.append((str(path.relative_to(root)), f"{owner}.{node.attr}"))
    return found


def test_the_readme_is_short_and_has_the_commands_a_newcomer_needs():
    text = README.read_text()
    assert len(text.splitlines()) <= 200, len(text.splitlines())
    for command in ("make sweep", "make test", "make test-generic", "study point"):
        assert command in text, command


def test_the_readme_states_the_code_s_default_method():
    # source: study/config.py's FIELDS (the default when a config sets no solver.method) and configs/default.toml
    from study.config import FIELDS_BY_PATH, load

    default = FIELDS_BY_PATH["solver.method"].default
    text = " ".join(README.read_text().split())
    assert f"the code's default is `{default}`" in text
    assert f'`solver.method = "{load(ROOT / "configs" / "default.toml").inputs["solver_method"]}"`' in text


def test_the_docs_tell_no_history_of_work_sessions():
    narrative = re.compile(r"\bsessions?\b|tried and not kept|\bbefore issue \d+|\bthis round\b", re.IGNORECASE)
    found = [f"{path.relative_to(ROOT)}:{number}: {line.strip()[:80]}"
             for path in sorted((ROOT / "docs").rglob("*.md")) + [README]
             for number, line in enumerate(path.read_text().splitlines(), 1) if narrative.search(line)]
    assert not found, "\n".join(found)


def test_the_crossing_finder_finds_both_forms(tmp_path):
    # a hand-made pair of modules: one import of a private name, one attribute read
    (tmp_path / "study").mkdir()
    user = tmp_path / "study" / "user.py"
    user.write_text("from study.owner import _hidden, shown\nimport study.owner as owner\nowner._other()\n")
    assert private_crossings([user], tmp_path) == [("study/user.py", "study.owner._hidden"),
                                                   ("study/user.py", "study.owner._other")]


def test_no_private_name_crosses_a_module():
    found = [f"{where}: {name}" for where, name in private_crossings() if (where, name) not in PRIVATE_CROSSINGS]
    assert not found, "private names used across modules (make them public):\n" + "\n".join(found)


def test_no_module_is_over_a_thousand_lines_but_the_listed():
    long = {str(path.relative_to(ROOT)): n for path in SOURCES
            if (n := len(path.read_text().splitlines())) > MAX_LINES}
    assert set(long) <= LONG_MODULES, long


def contact_law_forms(path: Path) -> list[str]:
    """The exponent forms of Hertz's law (:data:`CONTACT_LAW_FORM`) in the code of ``path``, each with its context."""
    tokens = tokenize.generate_tokens(io.StringIO(path.read_text()).readline)
    code = " ".join(t.string for t in tokens if t.type in (tokenize.NAME, tokenize.OP, tokenize.NUMBER))
    return [code[max(0, m.start() - 30):m.end()] for m in CONTACT_LAW_FORM.finditer(code)]


def test_the_law_finder_finds_the_forms_and_not_the_rest(tmp_path):
    # hand-made: the three forms in code; the same in a comment and a string, and other powers, are not the law
    source = tmp_path / "m.py"
    source.write_text('f = K * d**1.5\ne = 0.4 * K * d ** 2.5\ng = K * x * np.sqrt(x)\n'
                      '# K d**1.5\ns = "d ** 2.5"\nk = a**-1.5 + b**1.25 + c**15 + K * y * np.sqrt(z)\n')
    assert len(contact_law_forms(source)) == 3


def test_hertz_s_law_is_written_in_its_home_only():
    found = {str(path.relative_to(ROOT)): forms for path in SOURCES if (forms := contact_law_forms(path))}
    assert CONTACT_LAW_HOME in found
    stray = {where: forms for where, forms in found.items() if where != CONTACT_LAW_HOME
             and where not in CONTACT_LAW_LEFT}
    assert not stray, f"Hertz's law written out of {CONTACT_LAW_HOME} (call its functions):\n{stray}"


def test_no_solver_module_benchmarks_or_times_itself():
    # the benchmarks live in study/benchmarks/; the wall time is stamped once, by solve_point (study/solvers/__init__)
    found = []
    for path in sorted((ROOT / "study" / "solvers").rglob("*.py")):
        where = str(path.relative_to(ROOT))
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and re.search(
                    r"bench|penalty_reference|speedup|work_precision|convergence_table", node.name):
                found.append(f"{where}:{node.lineno}: defines {node.name}")
            if path.name != "__init__.py" and isinstance(node, ast.Attribute) and (
                    node.attr in ("perf_counter", "process_time", "monotonic")
                    or node.attr == "wall_time" and isinstance(node.ctx, ast.Store)):
                found.append(f"{where}:{node.lineno}: {node.attr}")
    assert not found, "\n".join(found)



def test_the_input_read_finder_finds_both_forms_outside_the_edge(tmp_path):
    # hand-made: a subscript and a get in a function, one on a Study's inputs; an assignment, a read in the edge's
    # builder, a read by a variable and a read of another dict are not counted
    (tmp_path / "study").mkdir()
    module = tmp_path / "study" / "m.py"
    module.write_text('def f(inputs, study, values):\n    a = inputs["outer_diameter"] / 2\n'
                      '    b = study.inputs.get("solver_method")\n    inputs["solver_method"] = "core"\n'
                      '    return values["x"] + values.get("y") + inputs[k]\n\n\nclass Scene:\n    def from_inputs(point):\n'
                      '        return point.get("restitution")\n')
    found = input_reads([module], tmp_path, edge={"study/m.py": {"Scene.from_inputs"}})
    assert found == ['study/m.py:2 (f): inputs["outer_diameter"]', 'study/m.py:3 (f): study.inputs.get("solver_method")']
    assert len(input_reads([module], tmp_path, edge={})) == 3


def test_the_inputs_are_read_by_name_only_where_the_point_is_made_and_typed():
    # issue 35: a parameter followed from the TOML to the physics by reading signatures: the solvers read the typed
    # Scene and options, built from the inputs in one place each
    found = input_reads()
    assert len(found) <= MAX_INPUT_READS, "inputs read by name outside the config, Scene.from_inputs and the options' " \
        "builders (read the Scene's or the options' field):\n" + "\n".join(found)


#: The kinds of study/solvers/ (issue 35): the model of a point and of a result, the compiled kernels, the methods.
SOLVERS = ROOT / "study" / "solvers"
#: What each kind may not import: the model no method nor kernel, the kernels no method.
LAYER_RULES = {"model": ("methods", "kernels"), "kernels": ("methods",)}
#: The ladder, which runs the other methods by design.
LADDER = "auto"
#: The methods that build on another, (importer, imported) -> why; every other sideways import fails the test. A method
#: that runs another at the same point reaches it through the registry (study.solvers.method), not by import.
METHOD_EDGES = {
    ("sliding", "reference"): "the sliding rest is the reference model's static equilibrium on its WhirlModel (built by "
                              "reference/model.py, which the reference method's kernel system grows in: moving it out "
                              "would move the reference model's own builder), and the state's window goes through the "
                              "reference model's stresses and whirl measure",
    ("reference", "sliding"): "the reference model's integration starts from the sliding rest in a deviated hole "
                              "(integrate.initial_state calls sliding.rest, which sliding's solver shares)",
    ("sliding", "sliding_parts"): "the sliding method's parts kept in a module of their own (sliding.py at the "
                                  "thousand-line cap): its checks of stability and of a second motion, the lift-off "
                                  "search's start",
    ("sliding_parts", "reference"): "the sliding state's checks run the reference model's integrator on its model "
                                    "(stability, from_rest)",
}


def _solvers_imports(path: Path, root: Path) -> list[tuple[str, ...]]:
    """The study.solvers sub-paths ``path`` imports anywhere (a lazy import in a function too), as tuples of names
    below study.solvers: ``from study.solvers.methods import sliding`` -> ('methods', 'sliding')."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("study.solvers"):
            found += [tuple(f"{node.module}.{alias.name}".split(".")[2:]) for alias in node.names]
        elif isinstance(node, ast.Import):
            found += [tuple(alias.name.split(".")[2:]) for alias in node.names
                      if alias.name.startswith("study.solvers")]
    return found


def solver_layer_breaches(paths=None, root: Path = ROOT) -> list[str]:
    """'file: kind imports target' for every import of study/solvers/'s model or kernels against
    :data:`LAYER_RULES`."""
    solvers = root / "study" / "solvers"
    found = []
    for path in paths if paths is not None else sorted(solvers.rglob("*.py")):
        kind = path.relative_to(solvers).parts[0]
        for target in _solvers_imports(path, root):
            if target and target[0] in LAYER_RULES.get(kind, ()):
                found.append(f"{path.relative_to(root)}: {kind} imports {'.'.join(target)}")
    return found


def sideways_imports(paths=None, root: Path = ROOT) -> set[tuple[str, str]]:
    """(importing method, imported method) for every import between two methods of study/solvers/methods/ (a method:
    one module or package there), the ladder's (:data:`LADDER`) left out."""
    methods = root / "study" / "solvers" / "methods"
    found = set()
    for path in paths if paths is not None else sorted(methods.rglob("*.py")):
        parts = path.relative_to(methods).with_suffix("").parts
        me = parts[0]
        if me in ("__init__", LADDER):
            continue
        for target in _solvers_imports(path, root):
            if len(target) > 1 and target[0] == "methods" and target[1] != me:
                found.add((me, target[1]))
    return found


def test_the_import_finders_find_a_hand_made_breach_and_sideways_import(tmp_path):
    # hand-made: a model module importing a kernel, a kernel importing a method lazily, a method importing two
    # others (one lazily, one through a package's module), the ladder importing a method, and allowed imports
    methods = tmp_path / "study" / "solvers" / "methods"
    for folder in ("model", "kernels", "methods/one", "methods"):
        (tmp_path / "study" / "solvers" / folder).mkdir(parents=True, exist_ok=True)
    model = tmp_path / "study" / "solvers" / "model" / "m.py"
    model.write_text("from study.physics import hertz\nfrom study.solvers.model import result\n"
                     "from study.solvers.kernels.whirl_kernel import step\n")
    kernel = tmp_path / "study" / "solvers" / "kernels" / "k.py"
    kernel.write_text("from study.solvers.model.scene import Scene\ndef f():\n    import study.solvers.methods.core\n")
    one = methods / "one" / "part.py"
    one.write_text("from study.solvers.methods.one import other\nfrom study.solvers.kernels import orbit\n"
                   "from study.solvers.methods.two.deep import x\n"
                   "def f():\n    from study.solvers.methods import three\n")
    ladder = methods / "auto.py"
    ladder.write_text("from study.solvers.methods import one, two\n")
    assert solver_layer_breaches([model, kernel], tmp_path) == [
        "study/solvers/model/m.py: model imports kernels.whirl_kernel.step",
        "study/solvers/kernels/k.py: kernels imports methods.core"]
    assert sideways_imports([one, ladder], tmp_path) == {("one", "two"), ("one", "three")}


def test_the_model_imports_no_method_nor_kernel_and_the_kernels_no_method():
    found = solver_layer_breaches()
    assert not found, "\n".join(found)


def test_a_method_imports_another_only_through_the_ladder_or_a_listed_edge():
    found = sideways_imports()
    stray = sorted(found - set(METHOD_EDGES))
    assert not stray, f"methods importing another (go through the model, the kernels or physics, or list the edge in " \
        f"METHOD_EDGES with its reason): {stray}"
    assert set(METHOD_EDGES) <= found, f"listed edges no longer taken (drop them): {sorted(set(METHOD_EDGES) - found)}"


def test_every_method_of_the_registry_takes_the_typed_point():
    # issue 35: the registry's functions take the DesignPoint solve_point builds once (a parameter followed from the
    # TOML to the physics by the signatures); each module keeps a thin solve(inputs) that builds it
    from study.solvers import METHOD_FUNCTIONS, METHOD_MODULES

    table = {name: (module, "run") for name, module in METHOD_MODULES.items()} | METHOD_FUNCTIONS
    for name, (module, function) in table.items():
        path = SOLVERS / "methods" / Path(*module.split("."))
        path = path / "__init__.py" if path.is_dir() else path.with_suffix(".py")
        tree = ast.parse(path.read_text())
        found = [node for node in tree.body if isinstance(node, ast.FunctionDef) and node.name == function]
        if not found and path.name == "__init__.py":  # a package: its method module (reference/method.py)
            found = [node for sub in path.parent.glob("*.py") for node in ast.parse(sub.read_text()).body
                     if isinstance(node, ast.FunctionDef) and node.name == function]
        assert len(found) == 1, (name, path)
        args = found[0].args.args
        assert len(args) == 1 and ast.unparse(args[0].annotation) == "DesignPoint", name


#: The thin wrappers a method module keeps for scripts and tests that hold a point's SI inputs: ``solve(inputs)`` (and
#: the ladder's ``solve_periodic``) build the typed point once and call the method.
INPUT_WRAPPERS = {"solve", "solve_periodic"}
#: Functions of a method or kernel that scripts, tests and the sliding state's parts still call with a point's SI
#: inputs, and type them on entry (``DesignPoint.of``: the point itself where typed, as the methods pass it).
TYPED_ENTRIES = {
    "study/solvers/methods/reference/model.py": {"build_model"},
    "study/solvers/methods/reference/method.py": {"simulate", "solve_with_modes"},
    "study/solvers/methods/reference/fields.py": {"stresses"},
    "study/solvers/methods/reference/statistics.py": {"cycle_values"},
    "study/solvers/methods/reference/replay.py": {"replay"},
    "study/solvers/kernels/modal_span.py": {"build_model", "simulate"},
}
#: Helpers of a method package for scripts and tests that hold a point's inputs, each with its reason.
INPUT_HELPERS = {
    ("study/solvers/methods/periodic/__init__.py", "options_from"): "the periodic options of a point's inputs, for "
                                                                    "validate.py and the periodic methods' tests",
}
#: Where a method still takes a point's inputs whole (``point.inputs``), each with its reason.
INPUTS_WHOLE = {
    ("study/solvers/methods/sliding.py", "run"): "the sliding state's solver takes the inputs (its functions are "
                                                 "another engineer's to retype)",
    ("study/solvers/methods/auto.py", "solve_rung"): "the ladder's cache key: the inputs but those the rung ignores",
    ("study/solvers/methods/periodic/__init__.py", "design_point"): "the periodic methods' finishers take the study "
                                                                    "tolerance from the inputs",
    ("study/solvers/methods/periodic/damped.py", "run"): "the damped stresses take the study tolerance from them",
}


def typed_point_breaches(paths=None, root: Path = ROOT) -> list[str]:
    """'file:line (function): call' for every ``X.from_inputs(...)`` or ``DesignPoint.of(...)`` in study/solvers/'s
    methods and kernels outside :data:`INPUT_WRAPPERS` (``DesignPoint.from_inputs`` there) and :data:`TYPED_ENTRIES`
    (``DesignPoint.of`` there), and every read of ``.inputs`` outside :data:`INPUTS_WHOLE`."""
    solvers = root / "study" / "solvers"
    found = []
    for path in paths if paths is not None else sorted(solvers.rglob("*.py")):
        where = str(path.relative_to(root))
        if path.relative_to(solvers).parts[0] not in ("methods", "kernels"):
            continue
        text = path.read_text()
        tree = ast.parse(text)
        functions = _qualified_functions(tree)
        for node in ast.walk(tree):
            function = functions.get(node, "")
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
                owner = ast.unparse(node.func.value)
                allowed = ((where, function) in INPUT_HELPERS
                           or node.func.attr == "from_inputs" and owner == "DesignPoint" and function in INPUT_WRAPPERS
                           or node.func.attr == "of" and owner == "DesignPoint"
                           and function in TYPED_ENTRIES.get(where, ()))
                typing = node.func.attr == "from_inputs" or node.func.attr == "of" and owner == "DesignPoint"
                if typing and not allowed:
                    found.append(f"{where}:{node.lineno} ({function or 'module'}): {ast.unparse(node)}")
            elif (isinstance(node, ast.Attribute) and node.attr == "inputs" and isinstance(node.ctx, ast.Load)
                  and (where, function) not in INPUTS_WHOLE):
                found.append(f"{where}:{node.lineno} ({function or 'module'}): {ast.unparse(node)}")
    return found


def test_the_typed_point_finder_finds_a_rebuild_and_a_whole_read(tmp_path):
    # hand-made: a method whose wrapper builds the point (allowed), a helper that rebuilds options and one that reads
    # the inputs whole (found), and a kernel that types inputs outside the listed entries (found)
    for folder in ("methods", "kernels"):
        (tmp_path / "study" / "solvers" / folder).mkdir(parents=True)
    method = tmp_path / "study" / "solvers" / "methods" / "m.py"
    method.write_text("def solve(inputs):\n    return run(DesignPoint.from_inputs(inputs))\n\n\n"
                      "def helper(point):\n    return ReferenceOptions.from_inputs(point.inputs)\n")
    kernel = tmp_path / "study" / "solvers" / "kernels" / "k.py"
    kernel.write_text("def f(point):\n    return DesignPoint.of(point)\n")
    assert typed_point_breaches([method, kernel], tmp_path) == [
        "study/solvers/methods/m.py:6 (helper): ReferenceOptions.from_inputs(point.inputs)",
        "study/solvers/methods/m.py:6 (helper): point.inputs",
        "study/solvers/kernels/k.py:2 (f): DesignPoint.of(point)"]


def test_a_method_takes_the_typed_point_and_rebuilds_nothing_from_the_inputs():
    # issue 35: the options and the scene are built once, by solve_point (or a module's solve(inputs) wrapper), and
    # passed down typed; a function that scripts or tests call with inputs types them on entry, listed
    found = typed_point_breaches()
    assert not found, "options or scene rebuilt from the inputs, or the inputs read whole, inside a method:\n" + \
        "\n".join(found)
    listed = {(where, function) for where, functions in TYPED_ENTRIES.items() for function in functions}
    for where, function in listed | set(INPUTS_WHOLE) | set(INPUT_HELPERS):
        tree = ast.parse((ROOT / where).read_text())
        assert any(isinstance(node, ast.FunctionDef) and node.name == function for node in ast.walk(tree)), \
            f"{where}: no function {function} (drop it from the list)"


#: Lines over :data:`MAX_LINE` characters in study/ (ruff's E501 at 120; ruff is not pinned) at most: those of the
#: compiled module study/physics/midspan.py, whose edit recompiles its kernels.
MAX_LINE = 120
MAX_LONG_LINES = 4


def test_the_long_lines_are_held_to_the_count_reached():
    long = [f"{path.relative_to(ROOT)}:{number}" for path in SOURCES
            for number, line in enumerate(path.read_text().splitlines(), 1) if len(line) > MAX_LINE]
    assert len(long) <= MAX_LONG_LINES, f"{len(long)} lines over {MAX_LINE} characters (wrap them):\n" + \
        "\n".join(long)
