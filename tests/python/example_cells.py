"""The `# %%` cells of docs/python_example.py, and what each prints when run in order in
one namespace (as a notebook runs them)."""
import contextlib
import io
import re

CELL = re.compile(r"^# %% (.*)$", re.MULTILINE)


def cells(script_text):
    """[(title, code)] of every `# %% title` cell; the text before the first is a comment."""
    parts = CELL.split(script_text)
    return [(parts[i].strip(), parts[i + 1].strip("\n")) for i in range(1, len(parts), 2)]


def outputs(script_text, filename):
    """What each cell prints, run one after the other in one namespace."""
    namespace = {"__name__": "__main__"}
    printed = []
    for _, code in cells(script_text):
        buffer = io.StringIO()
        with contextlib.redirect_stdout(buffer):
            exec(compile(code, filename, "exec"), namespace)
        printed.append(buffer.getvalue())
    return printed
