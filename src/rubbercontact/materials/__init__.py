"""Linear viscoelastic materials (generalized Maxwell / Prony series).

Presets (:func:`sbr`), Prony tables from files (:meth:`GeneralizedMaxwell.from_file`),
DMA data (:func:`read_dma`) and their Prony fit (:func:`fit_prony`), time–temperature
shift laws (:class:`WLF`, :class:`Arrhenius`) and master curves from isothermal sweeps
(:func:`master_curve`).
"""

from .dma import read_dma
from .dmadata import DMAData, DMAWarning, dma_from_material
from .fit import FitReport, PronyFit, fit_prony
from .master import MasterCurve, master_curve
from .maxwell import GeneralizedMaxwell, sbr
from .protocol import Material, PronyMaterial, check_material, check_prony
from .shift import WLF, Arrhenius, shift_law_from_dict
from .spec import load_material

__all__ = ["GeneralizedMaxwell", "sbr", "Material", "check_material", "PronyMaterial",
           "check_prony", "DMAData", "DMAWarning", "read_dma", "dma_from_material",
           "fit_prony", "FitReport", "PronyFit", "WLF", "Arrhenius", "shift_law_from_dict",
           "MasterCurve", "master_curve", "load_material"]
