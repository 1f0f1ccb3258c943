"""docs/python_api.md and the docstrings cover the whole public API: every name of
``rotorlanding.__all__`` has its row in the doc's table of public names and a docstring of its
own, every public member of the API classes is named in the doc, and every public method and
every API function has a docstring (what ``help()`` shows)."""

import inspect
import pydoc
import re
from pathlib import Path

import pytest

import rotorlanding as rl

DOC = (Path(__file__).resolve().parents[1] / "docs" / "python_api.md").read_text()


def _table_names() -> set[str]:
    """The names in the first column of the doc's "Public names" table."""
    section = DOC.split("## Public names", 1)[1].split("\n## ", 1)[0]
    return set(re.findall(r"^\| `([A-Za-z_]+)` \|", section, flags=re.M))


def test_every_public_name_has_a_row_in_the_doc_table():
    assert set(rl.__all__) - _table_names() == set()
    assert _table_names() - set(rl.__all__) == set(), "the doc names something the package does not export"


@pytest.mark.parametrize("name", [n for n in rl.__all__ if n != "__version__"])
def test_every_public_name_has_its_own_docstring(name):
    obj = getattr(rl, name)
    doc = vars(obj).get("__doc__") if isinstance(obj, type) else obj.__doc__  # a class: not inherited
    assert doc and len(doc.strip()) > 20, name
    if isinstance(obj, type):
        missing = [m for m, v in vars(obj).items() if not m.startswith("_") and inspect.isfunction(v)
                   and not (v.__doc__ or "").strip()]
        missing += [m for m, v in vars(obj).items() if isinstance(v, classmethod) and not (v.__func__.__doc__ or "").strip()]
        assert not missing, f"{name}: methods without a docstring: {missing}"
        base = set(dir(Exception))
        undocumented = [m for m in vars(obj) if not m.startswith("_") and m not in base and m not in DOC]
        assert not undocumented, f"{name}: members not named in docs/python_api.md: {undocumented}"
    else:
        assert f"## `{name}`" in DOC, f"{name} has no section in docs/python_api.md"


def test_version_is_the_package_version():
    assert isinstance(rl.__version__, str) and re.fullmatch(r"\d+\.\d+\.\d+\S*", rl.__version__)


@pytest.mark.parametrize("name, units", [("simulate", ["[s]", "[m]", "[N]", "[rpm]", "[J]", "[W]"]),
                                         ("coastdown", ["[s]", "[rpm]", "[J]", "[N]"]),
                                         ("sweep", ["[Hz]", "rpm"]), ("diagnose", ["[s]"])])
def test_help_of_the_functions_states_units(name, units):
    text = pydoc.render_doc(getattr(rl, name), renderer=pydoc.plaintext)
    for u in units:
        assert u in text, (name, u)
