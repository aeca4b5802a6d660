"""The gallery's pages show an example's warnings without the build machine's paths."""

import subprocess
import sys

SCRIPT = """
import warnings
import gallery_support
before = warnings.formatwarning
gallery_support.example_file({}, "examples/plot_x.py", "before")
warnings.warn("law at v=10 mm/s is extrapolated", RuntimeWarning)
gallery_support.example_file({}, "examples/plot_x.py", "after")
assert warnings.formatwarning is before
"""


def test_warnings_in_an_example_are_printed_without_paths(repo_root):
    # a process of its own: Python prints the warning to stderr, as in the gallery's build
    done = subprocess.run([sys.executable, "-c", SCRIPT], cwd=repo_root / "docs" / "_ext",
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stderr == "RuntimeWarning: law at v=10 mm/s is extrapolated\n"
