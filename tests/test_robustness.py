"""Property-based invariants and fuzzing of the readers (issue 7).

Invariants come from the definitions, not from earlier outputs:
- HDC >= 0; HDC(a z + b) = a^2 HDC(z) (quadratic in heights, blind to offsets);
- PSD integrates to the variance (Parseval);
- random or truncated bytes given to the profile readers raise only InputError, quickly.
"""

import time

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from rubbercontact.errors import InputError
from rubbercontact.io.profiles import read_profiles
from rubbercontact.roughness.statistics import hdc, psd, rms_height

heights = arrays(np.float64, st.integers(8, 200),
                 elements=st.floats(-10, 10, allow_nan=False, allow_infinity=False))


@settings(max_examples=60, deadline=None)
@given(z=heights, scale=st.floats(0.01, 100), offset=st.floats(-1e3, 1e3))
def test_hdc_nonnegative_quadratic_and_offset_blind(z, scale, offset):
    lags, r = hdc(z, 0.01)
    assert np.all(r >= 0)
    _, r2 = hdc(scale * z + offset, 0.01)
    # Floating-point: offsets up to 1e3 on heights ~10 lose ~1e-13 relative per difference.
    np.testing.assert_allclose(r2, scale**2 * r, rtol=1e-6, atol=1e-9 * scale**2 * (1 + r.max()))


@settings(max_examples=40, deadline=None)
@given(z=heights)
def test_psd_parseval(z):
    # The PSD's normalization (see psd docstring): sum over q of C(q) dq = variance.
    out = psd(z, 0.01)
    q, c = out[0], out[1]
    dq = q[1] - q[0] if q.size > 1 else 0.0
    var = rms_height(z) ** 2
    assert np.all(np.isfinite(c)) and np.all(c >= 0)
    np.testing.assert_allclose(np.sum(c) * dq, var, rtol=1e-8, atol=1e-12)


VALID_TEXT = b"# x [mm], z [mm]\n" + b"".join(
    f"{0.01 * i:.3f}, {np.sin(i / 7):.5f}\n".encode() for i in range(200))


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.one_of(st.binary(max_size=600),
                      st.integers(0, len(VALID_TEXT)).map(lambda k: VALID_TEXT[:k]),
                      st.text(max_size=300).map(str.encode)),
       fmt=st.sampled_from(["auto", "text", "captif"]))
def test_fuzz_profile_readers(tmp_path_factory, data, fmt):
    p = tmp_path_factory.mktemp("fuzz") / "scan.txt"
    p.write_bytes(data)
    t0 = time.perf_counter()
    try:
        read_profiles(p, format=fmt, dx=0.01)
    except InputError as exc:
        assert str(exc)
    assert time.perf_counter() - t0 < 5.0   # no hang: a few ms expected, 5 s is a bug
