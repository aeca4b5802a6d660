"""Reading measured roughness: line scans from text, CAPTIF and instrument files; height maps."""

from .maps import read_map, write_map
from .profiles import (
    Profiles,
    despike,
    detect_format,
    gap_free_windows,
    interpolate_gaps,
    profiles_from_arrays,
    read_captif,
    read_profiles,
    read_text,
    read_topography_file,
    trim_plates,
)

__all__ = ["Profiles", "despike", "detect_format", "gap_free_windows", "interpolate_gaps",
           "profiles_from_arrays", "read_captif", "read_profiles", "read_text",
           "read_topography_file", "trim_plates", "read_map", "write_map"]
