"""Read measured line scans into :class:`Profiles` (heights in mm, one sampling step).

One module per format reader (:mod:`.text`, :mod:`.captif`, :mod:`.topography`, and
:mod:`.arrays` for in-memory heights), the detection and dispatch in :mod:`.dispatch`,
the dropout/window/spike helpers in :mod:`.cleaning`, units and checks in
:mod:`.common`, the result in :mod:`.container`. Every public name is re-exported
here, so ``rubbercontact.io.profiles.<name>`` keeps working.

Formats
-------
``text``
    Plain text or CSV: one or many numeric columns; the delimiter (comma, semicolon,
    tab or blanks) is sniffed; header lines that are not numbers, and comment lines
    starting with ``#``, ``%`` or ``//``, are skipped; ``NaN`` or empty fields are
    dropouts. Either the sampling step ``dx`` [mm] is given and every column is a
    scan, or (``dx=None``) the first column (or ``x_column``) holds the positions and
    the other columns are scans. The numbers are in ``unit`` (``mm``, ``um``, ``nm``,
    ``m``, ``in``) and converted to mm.
``captif``
    The CAPTIF stationary laser profilometer: a tab-separated header, the line
    ``*****DATA*****``, then ``Data Point No:  Distance (mm)  Depth (mm)``. The
    instrument's reference plates (about 45 mm above the road) are trimmed, see
    :func:`trim_plates`.
``topography``
    Instrument formats (x3p, sur, opd, di, datx, plu, nc, …) through the optional
    SurfaceTopography package (``pip install rubbercontact[topography]``). A height map
    gives one scan per row along its first (x) axis.

Dropouts (NaN)
--------------
Leading and trailing NaN are always dropped. Inner gaps are handled by ``nan=``:

- ``"windows"`` (**default**): each scan that has gaps is cut into NaN-free windows
  of ``window`` mm (default 16 mm, the paper's scan length), consecutive windows of a
  gap-free stretch overlapping by ``window_overlap`` (default 0.5); gap-free scans are
  kept whole. No height is invented, but windows shorter than the gaps' spacing are
  lost, and dropouts tend to sit on steep flanks, so the windows under-sample them.
- ``"interpolate"``: straight lines across the gaps (keeps every length scale up to
  the scan length; the lines lower the HDC at lags shorter than the gaps).
- ``"error"``: raise :class:`InputError` naming the scan.

Spikes: ``despike=True`` replaces points that differ from the running median of
``despike_window`` points by more than ``despike_k`` scaled MADs (a Hampel filter).
"""

from __future__ import annotations

from .arrays import (
    profiles_from_arrays,
)
from .captif import (
    CAPTIF_MARKER,
    is_captif,
    plate_mask,
    read_captif,
    read_captif_raw,
    trim_plates,
)
from .cleaning import (
    despike,
    gap_free_windows,
    interpolate_gaps,
    strip_nan,
)
from .common import (
    SPACING_RTOL,
    UNITS_MM,
    Format,
    NanPolicy,
    check_plausible,
    sha256_file,
    uniform_step,
    unit_factor,
)
from .container import (
    Profiles,
)
from .dispatch import (
    detect_format,
    read_profiles,
)
from .text import (
    read_text,
    read_text_columns,
)
from .topography import (
    TOPOGRAPHY_EXTENSIONS,
    read_topography_file,
)

__all__ = [
    "CAPTIF_MARKER",
    "check_plausible",
    "despike",
    "detect_format",
    "Format",
    "gap_free_windows",
    "interpolate_gaps",
    "is_captif",
    "NanPolicy",
    "plate_mask",
    "Profiles",
    "profiles_from_arrays",
    "read_captif",
    "read_captif_raw",
    "read_profiles",
    "read_text",
    "read_text_columns",
    "read_topography_file",
    "sha256_file",
    "SPACING_RTOL",
    "strip_nan",
    "TOPOGRAPHY_EXTENSIONS",
    "trim_plates",
    "uniform_step",
    "unit_factor",
    "UNITS_MM",
]
