"""The tour notebook, examples/python/tour.ipynb, runs from top to bottom in a fresh kernel, and
its cells print what they say: passed droplets, a held-out value, a sweep's points."""
import os
import pathlib

import nbclient
import nbformat

TOUR = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "tour.ipynb"


def test_the_tour_notebook_runs_in_a_fresh_kernel(tmp_path, tmp_path_factory, monkeypatch):
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger note, not ours
    temp = tmp_path_factory.mktemp("temp")  # the kernel's temporary directory, which pytest clears
    monkeypatch.setenv("TMPDIR", str(temp))
    notebook = nbformat.read(TOUR, as_version=4)
    assert all(not c.get("outputs") for c in notebook.cells if c.cell_type == "code"), "commit it without outputs"
    nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    text = "".join(o.get("text", "") for c in notebook.cells if c.cell_type == "code" for o in c.outputs)
    assert "passed T =" in text and "<T> at dt/2" in text and "held out:" in text
    figures = sum(1 for c in notebook.cells if c.cell_type == "code" for o in c.outputs if "image/png" in o.get("data", {}))
    assert figures >= 6, figures  # paths, histogram, area trace, best curve, best medium, T(phi)
    assert list(tmp_path.iterdir()) == []  # its files went to its own temporary folder
    [work] = temp.iterdir()
    assert work.name.startswith("softdrop-tour-")
    assert {"search.db", "sweep.db"} <= {p.name for p in work.iterdir()}
