"""The Python examples of the READMEs run as printed (issue 32/33's outside-in audit: the
python/README.md "Use" block stopped at its last line on an undefined `heights`).

Each ```python block of README.md's "Using egw from Python" and python/README.md's "Use"
is executed as it stands, in a temporary working directory (it writes pair.bin), with
every warning an error: an example a user copies must neither fail nor warn. What the
examples compute is tested elsewhere (test_core, test_tables, test_topography); here the
checks are that they run and that the names they promise exist with the documented
shapes (the broadcast example's res.force.shape == (3, 4), its comment)."""
import os
import re
import warnings

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def python_blocks(path, section):
    """The ```python blocks of the Markdown section whose heading is `section`."""
    with open(os.path.join(REPO, path), encoding="utf-8") as f:
        text = f.read()
    start = text.index("\n" + section + "\n")
    end = text.find("\n## ", start + 1)
    part = text[start:end if end > 0 else len(text)]
    return re.findall(r"```python\n(.*?)```", part, flags=re.S)


@pytest.mark.parametrize("path, section", [
    ("README.md", "## Using egw from Python"),
    ("python/README.md", "## Use"),
])
def test_readme_python_runs_as_printed(path, section, tmp_path, monkeypatch):
    blocks = python_blocks(path, section)
    assert blocks, f"no python block under {section!r} in {path}"
    monkeypatch.chdir(tmp_path)
    for code in blocks:
        scope = {}
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            exec(compile(code, f"{path} ({section})", "exec"), scope)
        if "res" in scope:
            assert scope["res"].force.shape == (3, 4)
        if "params" in scope:      # the topography line returns egw.Params
            assert scope["params"].sigma > 0 and scope["params"].mu > 0
