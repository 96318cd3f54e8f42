"""The README's Python example runs as printed and says what it claims."""

from __future__ import annotations

import contextlib
import io
import os
import re

from conftest import ROOT


def test_the_readme_python_example_runs() -> None:
    readme = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", readme, flags=re.S)
    assert len(blocks) == 1, "one Python example in the README"
    out = io.StringIO()
    cwd = os.getcwd()
    try:
        os.chdir(ROOT)
        with contextlib.redirect_stdout(out):
            exec(compile(blocks[0], "README.md", "exec"), {})
    finally:
        os.chdir(cwd)
    printed = out.getvalue()
    # docs/your-own-domain.md's delivery example: the disturbed state joins L_8 after two actions.
    assert printed.startswith("joins L_8 after ['(load p4 van1 depot)'"), printed
    assert printed.rstrip().endswith("valid: True"), printed
