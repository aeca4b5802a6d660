"""Where a script's figure goes: a file always, and a window when there is a display.

``plt.show()`` alone draws nothing on a non-interactive backend (a terminal without a
display, a batch job, ``MPLBACKEND=Agg``) and warns that it cannot: a script run there
would leave its user without the figure it promised.
"""

from __future__ import annotations

from pathlib import Path

#: Folder (relative to the working directory) the example scripts write their figures to;
#: ``results/`` is where ``rubbercontact run`` writes too, and git ignores it.
EXAMPLE_FIGURES = Path("results") / "examples"


def show(fig, name: str, directory: str | Path = EXAMPLE_FIGURES) -> Path:
    """Save ``fig`` as ``directory/name`` (PNG unless ``name`` says otherwise), print where,
    and show it too when matplotlib's backend is interactive.

    Parameters
    ----------
    fig
        A matplotlib figure.
    name
        File name, e.g. ``"quickstart_halfspace.png"``.
    directory
        Folder, created if missing; relative to the working directory.

    Returns
    -------
    Path
        The file written.
    """
    import matplotlib
    import matplotlib.pyplot as plt

    path = Path(directory) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=130)
    print(f"figure: {path}")
    # matplotlib's non-interactive built-in backends (its backend_registry needs >= 3.9)
    if matplotlib.get_backend().lower() not in {"agg", "cairo", "pdf", "pgf", "ps", "svg",
                                                "template"}:
        plt.show()
    return path
