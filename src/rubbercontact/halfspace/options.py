"""Algorithm switches of the half-space solver, in one frozen options object.

The defaults are the fastest paths; each is tested against the plain path it replaces
(``tests/test_halfspace*.py``), and the other settings exist for those comparisons and for the
benchmarks (``benchmarks/bench_halfspace.py``, figures in ``benchmarks/halfspace.md``).
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass, fields

from ..errors import InputError

__all__ = ["SolverOptions"]

#: Grids are coarsened by this factor per level of the multilevel starts.
COARSE_FACTOR = 4
#: Maps of fewer points keep double precision in the contact-set solves and the plain
#: preconditioners: an FFT pair in single precision costs nearly a double one on small
#: maps (the double-precision transforms leave the cache from 256² on; figures in
#: ``benchmarks/maps.md``), and the round-off of a single-precision solve breaks
#: symmetries that small test maps pin (μ = 0 to 1e-12 on an elastic map).
SINGLE_MIN_POINTS_2D = 256 * 256
#: Float options that may exceed 1 (any positive value); the others lie in (0, 1).
_POSITIVE = ("soft_law_scale_beta_2d",)


@dataclass(frozen=True)
class SolverOptions:
    """Algorithm switches of :func:`~rubbercontact.halfspace.solve_sliding`.

    Attributes
    ----------
    complex_preconditioner : bool, default True
        Precondition the contact-set systems by the stiffness ``1/(M + c̄)`` of the full
        complex compliance; ``False``: ``1/(Re M + c̄)`` of its Hermitian part.
    complex_preconditioner_maxiter : int, default 150
        GMRES iterations allowed with the complex preconditioner before the Hermitian one
        takes over.
    multi_shift : bool, default True
        In the Newton systems of a law, the variable-coefficient preconditioner
        ``1/(M(q) + c(x))`` (interpolated between three shifts) once enough points are stiff.
    multi_shift_min_points : int, default 32
        Points with ``c > 10 c̄`` needed before the multi-shift preconditioner is used.
    dense_max_points : int, default 256
        1D grids of at most this many points solve the contact-set systems directly (dense
        bordered matrix); 0: GMRES on every grid.
    dense_max_set : int, default 1024
        1D contact sets of at most this many points solve the contact-set systems directly
        on any grid (the set's block of the circulant ``M``, gathered from one column);
        0: only grids of at most ``dense_max_points`` points.
    reuse_dense_factorization : bool, default True
        A dense contact-set solve on the same set as the previous one (on the same
        problem) refines from the previous solve's single-precision LU before factorising
        anew (:func:`~rubbercontact.halfspace.contact_set.mixed_precision_solve`).
    coarse_min_points : int or None, default 256
        Smallest grid of the coarse-grid start of the viscoelastic hard wall: a 1D grid of
        ``N >= 4 × coarse_min_points`` points, ``N`` divisible by 4, starts from the solution
        on every 4th point (recursively). ``None``: no coarse-grid start.
    coarse_polish_updates : int, default 16
        Active-set updates allowed to polish an interpolated coarse-grid hard-wall solution.
    mixed_newton : bool, default True
        Lennard-Jones wall alone: rows in contact linearised on the inverse law (mixed
        Newton); ``False``: plain Newton on ``σ = f(u)``.
    wall_soft_active_set : bool, default True
        Lennard-Jones wall + soft law: solve "hard wall + soft law" by the semismooth
        active-set Newton first; ``False``: only the continuation ``wall + s·soft``, ``s: 0 → 1``.
    wall_soft_coarse_min_points : int or None, default 256
        As ``coarse_min_points``, for the hard wall + soft law stage.
    wall_soft_linear_rtol : float, default 1e-3
        GMRES tolerance of one step of the hard wall + soft law active-set Newton.
    wall_soft_linear_rtol_2d : float, default 1e-2
        ``wall_soft_linear_rtol`` on maps. The steps of the hard wall + soft law are as many
        at 1e-2 as at 1e-3 (the contact set, not the linear solve, limits them), with fewer
        GMRES iterations: the 1024² linear-law case of ``benchmarks/maps.md`` 16.1 → 12.0 s
        CPU; 3e-2 took one step more (13.4 s).
    coarse_min_side_2d : int or None, default 128
        Maps: smallest side of the coarse-grid starts (viscoelastic hard wall, hard wall +
        soft law, elastic active set); a map of even sides at least twice this starts from
        the solution on every 2nd point of each axis (recursively). ``None``: no coarse-grid
        start on maps. The 1D switches above (``None``) turn it off as well.
    wall_soft_mixed_newton_2d : bool, default True
        Maps: the final Newton of a Lennard-Jones wall + soft law linearises the wall's
        contact rows in the wall's inverse form (the mixed Newton with a soft member);
        ``False``: the plain Newton there.
    wall_soft_first_tangent_2d : bool, default True
        Maps: the first step of that mixed Newton takes the tangent of the wall's inverse at
        the wall's share of the pressure instead of the geometric mean with ``f_w(u)``
        (:func:`~rubbercontact.halfspace.newton._wall_soft_rows`): 4 instead of 5 steps on
        the 1024² linear-law case of ``benchmarks/maps.md``.
    multi_shift_2d : bool, default False
        Maps: ``multi_shift`` also on maps. Off by default: on the self-affine maps of
        ``benchmarks/maps.md`` it saved no GMRES iterations and doubled their FFTs.
    single_krylov_2d : bool, default True
        With ``single_precision_2d``: the GMRES iterations of a single-precision cycle to a
        tolerance of at least 1e-3 (the loose steps) keep their Krylov basis in float32 as
        well (their operator rounds to float32; the double-precision residual still ends
        the solve); ``False``: a float64 basis. Tighter cycles keep float64 unless
        ``tight_krylov32_2d`` (on the Lennard-Jones wall alone unguarded float32 ones once
        stalled the last Newton steps).
    soft_law_preconditioner_2d : bool, default True
        Maps of at least 256² points: contact-set systems of which at least a tenth of the
        rows carry a local compliance ``c`` above the diagonal of ``M`` (a soft law) are
        preconditioned by the variable-coefficient stiffness ``1/(M(q) + c(x))`` over all
        rows (:mod:`~rubbercontact.halfspace.contact_set`); ``False``: ``1/(M + c̄)`` on the
        rows with ``c`` below the diagonal and the diagonal ``1/(c + m_d)`` on the others.
    soft_law_low_quantile_2d : float, default 0.02
        The lowest shift of the soft-law preconditioner is this quantile of the set's
        positive ``c`` (the highest is the largest ``c``), at least
        ``soft_law_lowest_shift_2d``.
    soft_law_lowest_shift_2d : float, default 0.3
        The lowest shift is at least this many times ``m_d`` (the diagonal of ``M``):
        rows with ``c`` well below ``m_d`` are hard to the preconditioner whatever their
        ``c``, and a shift spent there is lost.
        On the 1024² linear-law case of ``benchmarks/maps.md`` 0.3 instead of 1e-3 moves
        the lowest shift from 0.13 to 0.3 ``m_d`` in the hard wall + soft law steps and
        from 4e-5 to 0.3 ``m_d`` in the Newton steps (their wall rows): 3025 → 2696 FFT
        pairs with ``soft_law_shifts_2d = 2`` (512²: 1897 → 1773); the FEM-like table,
        whose ``c`` all exceed 17 ``m_d``, is untouched (417 pairs). The 0.2 quantile
        instead did as well on the linear law (2701) but cost the FEM-like table 482;
        a floor of ``m_d`` cost the Newton steps 60 % more iterations.
    soft_law_shifts_2d : int, default 2
        Shifts of the soft-law preconditioner in the other systems on maps (the Newton
        steps) when ``soft_law_scaled_2d`` is off. With the lowest shift at least 0.3
        ``m_d`` (``soft_law_lowest_shift_2d``)
        two take as many GMRES iterations as three (the 1024² linear-law case of
        ``benchmarks/maps.md``: final Newton 113 both; measured with the lowest shift at
        the 0.2 quantile, 0.17 ``m_d`` there: 2814 → 2701 FFT pairs); with it at 4e-5
        ``m_d`` two took 40 % more.
    soft_law_scaled_2d : bool, default True
        The soft-law preconditioner as one kernel ``1/(M + s)`` at its lowest shift with
        each row's output scaled by ``(4 m_d + s)/(4 m_d + c)``
        (:func:`~rubbercontact.halfspace.precond.scaled_kernel`) instead of the kernels
        of ``soft_law_shifts_2d`` (or ``wall_soft_shifts_2d``) shifts interpolated in
        ``log c``: one inverse FFT per application instead of two.
    wall_soft_coarse_min_side_2d : int or None, default 64
        Maps: ``coarse_min_side_2d`` for the hard wall + soft law stage (``None``: that
        one); ``coarse_min_side_2d = None`` still turns every coarse start off. Its
        coarsest grid solves the soft law alone by Newton from the Winkler pressure, in
        many steps; on a coarser grid they cost less, and the next grid starts from there.
    reuse_response_2d : bool, default True
        Maps: a hard wall + soft law step's displacement ``M δσ`` is the sum of
        its off-set part's and the contact-set solve's last response
        (:func:`~rubbercontact.halfspace.contact_set.step_displacement`) instead of a
        transform of its own: one double-precision FFT pair less per step.
    wall_soft_moving_rtol_2d : float or None, default 5e-2
        Maps: the GMRES tolerance of a hard wall + soft law step while its contact set
        still moves (the first step, and after an update that changed more than 1 % of
        the set); ``None``: ``wall_soft_linear_rtol_2d`` throughout.
    wall_soft_coarse_tol_2d : float or None, default 1e-6
        Maps: the coarser grids of the hard wall + soft law stage stop at this tolerance
        (or ``tol`` if larger) instead of ``tol``: their answer is only the finer grid's
        start, and the finer grid takes as many steps from it (the 1024² linear-law case of
        ``benchmarks/maps.md``: 9 on 1024², 7 instead of 9 on 512² and 256², 3209 instead
        of 3446 FFT pairs; 1e-5 saved one more 512² step and cost two finer GMRES
        iterations). ``None``: ``tol`` on every grid.
    wall_soft_shifts_2d : int, default 2
        Shifts of the soft-law preconditioner (``soft_law_preconditioner_2d``) in the
        systems of the hard wall + soft law steps on maps when ``soft_law_scaled_2d`` is
        off; the Newton steps keep three.
        Those steps' systems, solved to ``wall_soft_linear_rtol_2d``, take as many GMRES
        iterations with two shifts as with three, at three FFTs per iteration instead of
        four (the 1024² linear-law case of ``benchmarks/maps.md``: 162 against 160
        iterations, 532 against 686 FFT pairs on the finest grid); the Newton steps took
        40 % more iterations with two.
    split_inverse_fft_2d : bool, default True
        Maps: the inverse FFTs of the solver run as a complex pass along ``y`` and a real
        one along ``x`` (:func:`~rubbercontact.halfspace.kernels.inverse`) instead of
        scipy's ``irfftn``: the same transform (bitwise when ``ny`` is a power of two),
        half the time in float64 and three quarters in float32 at 1024²; ``False``:
        ``irfftn``.
    newton_forcing_target_2d : bool, default True
        Maps: the GMRES tolerance of a Newton step is at least ``0.01 tol/res`` (a step need
        not solve its linear system further than the tolerance asks); ``False``: at least
        ``tol`` (:func:`~rubbercontact.halfspace.newton._newton_rtol`).
    exact_load_2d : bool, default True
        Maps: a Newton step whose load correction ``σ0 n − Σσ − Σ δσ_free`` is at the
        load's round-off (``halfspace.newton._LOAD_ROUNDOFF`` of ``σ0 n``) solves its
        system with none. The contact-set solve spreads the correction uniformly over the set
        and measures its GMRES tolerance against the residual of that start; on the rows
        with a large local compliance (the Lennard-Jones wall's tail) an ulp of the load
        became a residual far above the Newton residual near ``tol``, so the step's
        tolerance (``newton_forcing_target_2d``) asked for nothing and the Newton stalled
        (``benchmarks/maps.md``). ``False``: the correction as computed.
    tight_krylov32_2d : bool, default True
        With ``single_krylov_2d``: the single-precision cycles tighter than 1e-3 (the last
        Newton steps) keep a float32 Krylov basis too, down to the cycles' floor 1e-5;
        a tight cycle whose double-precision residual ends more than ten times above its
        target leaves the rest of that solve to a float64 basis. The same iterations and
        answers to round-off on the maps of ``benchmarks/maps.md`` (the 1024² linear law:
        786 iterations either way, CGS2 on half the bytes); the Lennard-Jones wall alone,
        whose Newton once stalled with float32 tight cycles, converges (512²: 3113 against
        3117 FFT pairs). ``False``: float64 bases below 1e-3.
    krylov_workspace_2d : bool, default True
        Maps (the single-precision cycles): the GMRES bases are kept between a problem's
        contact-set solves instead of allocated per restart cycle (tens of MB on a 1024²
        contact set, whose pages the system hands out afresh, with a fault per page, at
        every allocation); bitwise the same iterates.
    wall_soft_skip_level_2d : bool, default True
        Maps: the finest grid of the hard wall + soft law stage starts from the grid 4×
        coarser per axis (the level between is skipped; coarser levels keep halving):
        that level's updates cost more than the one finest update they spare
        (:func:`~rubbercontact.halfspace.walls._start_grid`). ``False``: every level.
    coarse_space_2d : int or None, default 16
        Maps: the soft-law preconditioner (``soft_law_preconditioner_2d``) and the hard
        wall's add a coarse space, piecewise constant on the set's points in each of
        ``k × k`` blocks of the grid (``k`` this value;
        :mod:`~rubbercontact.halfspace.twolevel`): the one-level output keeps its part of
        zero mean per block, a dense coarse system supplies the means. Fewer GMRES
        iterations in every such system, at two sums over the set per iteration
        (``benchmarks/maps.md``). ``None``, or sides not divisible into blocks of at least
        two points: the one-level preconditioners. The Lennard-Jones wall's Newton systems
        (the shifted kernel and a diagonal) keep theirs.
    coarse_space_min_side_2d : int, default 512
        The coarse space of ``coarse_space_2d`` on maps whose sides are at least this:
        the smooth modes it treats are the worse conditioned the finer the grid (the
        ratio of ``M`` at the lowest wavenumber to ``m_d`` grows with the side), and at
        256² the one-level iterations were as few (``benchmarks/maps.md``).
    soft_law_scale_beta_2d : float, default 2.0
        ``β`` of the row scaling ``(β m_d + s)/(β m_d + c)`` of the soft-law
        preconditioner (:func:`~rubbercontact.halfspace.precond.scaled_kernel`). 2 with the
        coarse space of ``coarse_space_2d``; 4 was the one-level choice, and with the
        coarse space takes more GMRES iterations (``benchmarks/maps.md``).
    single_precision_2d : bool, default True
        Maps of at least 256² points: the GMRES iterations of the contact-set systems apply
        the operator and the
        preconditioner with single-precision FFTs, and double-precision residuals refine the
        solution to the requested tolerance (:mod:`~rubbercontact.halfspace.contact_set`).
    """

    complex_preconditioner: bool = True
    complex_preconditioner_maxiter: int = 150
    multi_shift: bool = True
    multi_shift_min_points: int = 32
    dense_max_points: int = 256
    dense_max_set: int = 1024
    reuse_dense_factorization: bool = True
    coarse_min_points: int | None = 256
    coarse_polish_updates: int = 16
    mixed_newton: bool = True
    wall_soft_active_set: bool = True
    wall_soft_coarse_min_points: int | None = 256
    wall_soft_linear_rtol: float = 1e-3
    wall_soft_linear_rtol_2d: float = 1e-2
    coarse_min_side_2d: int | None = 128
    wall_soft_mixed_newton_2d: bool = True
    wall_soft_first_tangent_2d: bool = True
    multi_shift_2d: bool = False
    single_precision_2d: bool = True
    soft_law_preconditioner_2d: bool = True
    wall_soft_shifts_2d: int = 2
    wall_soft_coarse_tol_2d: float | None = 1e-6
    wall_soft_moving_rtol_2d: float | None = 5e-2
    newton_forcing_target_2d: bool = True
    split_inverse_fft_2d: bool = True
    soft_law_low_quantile_2d: float = 0.02
    soft_law_lowest_shift_2d: float = 0.3
    soft_law_shifts_2d: int = 2
    single_krylov_2d: bool = True
    soft_law_scaled_2d: bool = True
    reuse_response_2d: bool = True
    wall_soft_coarse_min_side_2d: int | None = 64
    tight_krylov32_2d: bool = True
    exact_load_2d: bool = True
    krylov_workspace_2d: bool = True
    wall_soft_skip_level_2d: bool = True
    coarse_space_2d: int | None = 16
    coarse_space_min_side_2d: int = 512
    soft_law_scale_beta_2d: float = 2.0

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            name = f"options.{f.name}"
            if f.type == "bool":
                if not isinstance(value, bool):
                    raise InputError(f"{name}: expected True or False, got {value!r}")
            elif f.name in _POSITIVE:
                if isinstance(value, bool) or not isinstance(value, numbers.Real) \
                        or not 0.0 < value < float("inf"):
                    raise InputError(f"{name}: expected a number > 0, got {value!r}")
            elif f.type.startswith("float"):
                if value is None and "None" in f.type:
                    continue
                if isinstance(value, bool) or not isinstance(value, numbers.Real) \
                        or not 0.0 < value < 1.0:
                    raise InputError(f"{name}: expected a number in (0, 1), got {value!r}")
            elif value is not None or "None" not in f.type:
                smallest = {"dense_max_points": 0, "dense_max_set": 0,
                            "wall_soft_shifts_2d": 2, "soft_law_shifts_2d": 2}.get(f.name, 1)
                if isinstance(value, bool) or not isinstance(value, numbers.Integral) \
                        or value < smallest:
                    allowed = " or None" if "None" in f.type else ""
                    raise InputError(f"{name}: expected an integer >= {smallest}{allowed}, "
                                     f"got {value!r}")
