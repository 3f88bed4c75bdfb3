"""The package's type stubs: they name what the module has (mypy's stubtest against the module as
built), and a type checker passes a right call and catches a wrong one, as an editor would."""
import os
import pathlib
import subprocess
import sys

import pytest

import softdrop

pytest.importorskip("mypy")

HERE = pathlib.Path(__file__).resolve().parent
PACKAGE_ROOT = pathlib.Path(softdrop.__file__).resolve().parents[1]  # the folder softdrop/ is in


def mypy(tmp_path, *args):
    config = tmp_path / "mypy.ini"
    # Debian's pandas and matplotlib have no stubs; the cache goes with the test's files.
    config.write_text(f"[mypy]\nignore_missing_imports = True\ncache_dir = {tmp_path / 'cache'}\n")
    env = dict(os.environ, MYPYPATH=str(PACKAGE_ROOT))
    option = "--config-file" if args[0] == "mypy" else "--mypy-config-file"
    return subprocess.run([sys.executable, "-m", *args, option, str(config)], capture_output=True, text=True,
                          cwd=PACKAGE_ROOT, env=env)


def test_the_stubs_name_what_the_module_has(tmp_path):
    r = mypy(tmp_path, "mypy.stubtest", "softdrop", "--allowlist", str(HERE / "stubtest_allowlist.txt"))
    assert r.returncode == 0, r.stdout + r.stderr


def test_a_type_checker_passes_right_calls_and_catches_wrong_ones(tmp_path):
    right = tmp_path / "right.py"
    right.write_text(
        "import softdrop\n"
        "m = softdrop.Medium.generate('non-overlapping', porosity=0.8, seed=1)\n"
        "run = softdrop.simulate(m, x0=200.0, params=softdrop.DropletParams(radius=8), path=True)\n"
        "frame = softdrop.simulate_many(m, 20, seed=3)\n"
        "r: float = m.porosity() + m.grains[0, 2] + softdrop.DropletParams.balloon().radius\n"
        "softdrop.optimize('s.db', generations=3, callback=lambda e: e['generation'] < 2)\n")
    r = mypy(tmp_path, "mypy", str(right))
    assert r.returncode == 0, r.stdout
    wrong = tmp_path / "wrong.py"
    wrong.write_text(
        "import softdrop\n"
        "m = softdrop.Medium.generate(porosity='0.8')\n"
        "softdrop.simulate(m, x0='left')\n"
        "softdrop.DropletParams().radius = 'big'\n"
        "softdrop.read_history(3)\n")
    r = mypy(tmp_path, "mypy", str(wrong))
    assert r.returncode == 1
    lines = {int(line.split(":")[1]) for line in r.stdout.splitlines() if "error:" in line}
    assert lines == {2, 3, 4, 5}, r.stdout


def test_the_stubs_name_every_keyword_of_the_parameter_types():
    # The stubs list DropletParams' and RunOptions' keywords one by one (so editors complete them):
    # exactly the attributes the module has, which __init__'s docstring lists with their defaults.
    import ast

    # DropletParams' part is written by the build from the droplet's list of fields; each keyword
    # and attribute is annotated with the type of its default.
    tree = ast.parse((pathlib.Path(softdrop.__file__).parent / "_core.pyi").read_text())
    for cls in (softdrop.DropletParams, softdrop.RunOptions):
        stub = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls.__name__)
        init = next(n for n in stub.body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
        keywords = [a.arg for a in init.args.kwonlyargs]
        defaults = cls().__getstate__()
        assert keywords == list(defaults), cls.__name__
        attributes = {n.target.id: n.annotation.id for n in stub.body if isinstance(n, ast.AnnAssign)}
        assert list(attributes) == keywords, cls.__name__
        for a in init.args.kwonlyargs:
            assert a.annotation.id == attributes[a.arg] == type(defaults[a.arg]).__name__, (cls.__name__, a.arg)
            assert f"    {a.arg} (" in cls.__init__.__doc__


def test_the_stub_writer_refuses_a_template_without_its_one_marker_and_writes_nothing(tmp_path):
    # The build's writer of _core.pyi (python/droplet_stub.cpp), beside the module in a build tree.
    writer = PACKAGE_ROOT / "droplet_stub"
    if not writer.exists():
        pytest.skip("an installed package: the stub writer is in the build tree only")
    source = HERE.parents[1] / "python" / "softdrop" / "_core.pyi.in"
    template = source.read_text()
    out = tmp_path / "_core.pyi"
    r = subprocess.run([str(writer), str(source), str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.read_text() == (pathlib.Path(softdrop.__file__).parent / "_core.pyi").read_text()
    marker = "    @DROPLET_PARAMS_FIELDS@\n"
    for bad, times in ((template.replace(marker, ""), 0), (template + marker, 2)):
        (tmp_path / "bad.pyi.in").write_text(bad)
        r = subprocess.run([str(writer), str(tmp_path / "bad.pyi.in"), str(tmp_path / "bad.pyi")],
                           capture_output=True, text=True)
        assert r.returncode == 1
        assert r.stderr == f"droplet_stub: {tmp_path / 'bad.pyi.in'}: needs the line @DROPLET_PARAMS_FIELDS@ once, " \
                           f"not {times} times\n"
        assert sorted(p.name for p in tmp_path.iterdir()) == ["_core.pyi", "bad.pyi.in"]


def test_the_package_shows_its_api_and_only_that():
    # What a user's tab completion lists is __all__ (and the plot submodule once imported): no
    # module the package itself imports; and each name says what it is.
    public = {n for n in dir(softdrop) if not n.startswith("_")} - {"plot"}
    assert public == set(softdrop.__all__) - {"__version__"}
    for name in public:
        assert (getattr(softdrop, name).__doc__ or "").strip(), name
