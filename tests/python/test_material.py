"""ecm.Material and the point update from Python. Expected values: elasticity (a : eps), the
consistent tangent against central differences, the band dissipating G_F = 0.11 N/mm (the
paper's concrete, calibrated E_p = 8.184 MPa for n = 0.128, h = 0.05 mm), and the C++ update
itself (update_many against a loop of update, pickling)."""
import copy
import pickle

import numpy as np
import pytest

import ecm

CONCRETE = dict(name="concrete", model="enriched", hypothesis="plane_stress", youngs_modulus=32000,
                poisson_ratio=0.2, tensile_strength=3.0, softening_modulus=8.184, softening_exponent=0.128,
                band_width=0.05, fracture_energy=0.11)


def cracked_point(material, H=10.0):
    """A point pulled in x past onset, into softening."""
    p = ecm.PointState()
    for _ in range(120):
        r = material.update(p, [1e-6, 0.0, 0.0], H)
        assert r.converged
    assert p.band is not None
    return p


def test_keywords_dict_and_file_give_the_same_material(source):
    from_file = ecm.Material.from_file(source / "data/materials/den-concrete.yaml")
    from_keys = ecm.Material(**CONCRETE)
    from_dict = ecm.Material.from_dict(CONCRETE)
    for m in (from_keys, from_dict):
        a, b = ecm.PointState(), ecm.PointState()
        for _ in range(150):
            ra = from_file.update(a, [1e-6, -2e-7, 1e-7], 10.0)
            rb = m.update(b, [1e-6, -2e-7, 1e-7], 10.0)
            assert np.array_equal(ra.stress, rb.stress)
        assert a.band.integrity == b.band.integrity


def test_an_intact_point_is_linear_elastic():
    m = ecm.Material(**CONCRETE)
    p = ecm.PointState()
    eps = np.array([2e-5, -1e-5, 3e-5])
    r = m.update(p, eps, 10.0)
    assert r.converged and r.status == "converged" and r.dissipation == 0.0
    np.testing.assert_allclose(r.stress, m.stiffness @ eps, rtol=1e-14)
    np.testing.assert_array_equal(p.strain, eps)
    assert p.band is None and p.damage == 0.0


def test_the_tangent_of_a_softening_point_is_the_derivative_of_its_stress():
    m = ecm.Material(**CONCRETE)
    base = cracked_point(m)
    d = np.array([1e-6, 2e-7, -3e-7])
    tangent = m.update(copy.deepcopy(base), d, 10.0).tangent
    step = 1e-10
    numeric = np.zeros((3, 3))
    for j in range(3):
        e = np.zeros(3)
        e[j] = step
        plus, minus = copy.deepcopy(base), copy.deepcopy(base)
        numeric[:, j] = (m.update(plus, d + e, 10.0).stress - m.update(minus, d - e, 10.0).stress) / (2 * step)
    np.testing.assert_allclose(tangent, numeric, rtol=1e-4, atol=1e-4 * np.abs(numeric).max())


def test_the_band_dissipates_the_fracture_energy_in_uniaxial_tension():
    # Strain control in x to full separation, H = 10 mm (no snap-back below ~196 mm): H times
    # the dissipation per volume is G_F = 0.11 N/mm (what E_p was calibrated for). The lateral
    # strain is held at 0, so the band also sees a small sliding-free plane-stress-like path:
    # the tolerance is the calibration's and the increments' (1 %).
    m = ecm.Material(**CONCRETE)
    p = ecm.PointState()
    dissipated = 0.0
    for _ in range(2000):
        r = m.update(p, [2.5e-5, 0.0, 0.0], 10.0, substep_levels=6)
        assert r.converged
        dissipated += r.dissipation
    assert p.band.damage > 0.999
    assert 10.0 * dissipated == pytest.approx(0.11, rel=0.01)


def test_states_round_trip_through_pickle_and_copy():
    m = ecm.Material(**CONCRETE)
    p = cracked_point(m)
    for q in (pickle.loads(pickle.dumps(p)), copy.deepcopy(p), copy.copy(p)):
        np.testing.assert_array_equal(q.strain, p.strain)
        assert q.band.integrity == p.band.integrity
        np.testing.assert_array_equal(q.band.jump, p.band.jump)
        np.testing.assert_array_equal(q.band.crack_normal, p.band.crack_normal)
        np.testing.assert_array_equal(q.band.onset_strain, p.band.onset_strain)
        assert q.band.volume_fraction == p.band.volume_fraction
        # and the copy goes on exactly as the original
        a, b = copy.deepcopy(p), q
        assert np.array_equal(m.update(a, [1e-6, 0, 0], 10.0).stress, m.update(b, [1e-6, 0, 0], 10.0).stress)
    array = ecm.PointArray([p, ecm.PointState()])
    back = pickle.loads(pickle.dumps(array))
    assert len(back) == 2 and back[0].band.integrity == p.band.integrity and back[1].band is None


def test_update_many_equals_a_loop_of_update():
    m = ecm.Material(**CONCRETE)
    rng = np.random.default_rng(7)
    n = 200
    start = [cracked_point(m) if i % 3 == 0 else ecm.PointState(rng.uniform(-5e-5, 5e-5, 3)) for i in range(n)]
    points = ecm.PointArray(start)
    loop = [copy.deepcopy(p) for p in start]
    H = rng.uniform(5.0, 50.0, n)
    for _ in range(5):
        d = rng.uniform(-2e-5, 4e-5, (n, 3))
        many = m.update_many(points, d, H, tangent=True, snap_back="release", substep_levels=4)
        for i in range(n):
            r = m.update(loop[i], d[i], H[i], tangent=True, snap_back="release", substep_levels=4)
            assert np.array_equal(many["stress"][i], r.stress)
            assert np.array_equal(many["tangent"][i], r.tangent)
            assert many["dissipation"][i] == r.dissipation
            assert ecm.STATUS[many["status"][i]] == r.status
    np.testing.assert_array_equal(points.strain, np.array([p.strain for p in loop]))
    np.testing.assert_array_equal(points.damage, np.array([p.damage for p in loop]))


def test_bad_parameters_are_refused_naming_the_key():
    bad = dict(CONCRETE, tensile_strength=-3.0)
    with pytest.raises(ValueError, match="tensile_strength"):
        ecm.Material(**bad)
    with pytest.raises(ecm.InputError, match="unknown key 'youngs_modulos'|youngs_modulos"):
        ecm.Material(**dict(CONCRETE, youngs_modulos=1.0))
    m = ecm.Material(**CONCRETE)
    with pytest.raises(ValueError, match="shape"):
        m.update_many(ecm.PointArray(3), np.zeros((2, 3)), 10.0)
    with pytest.raises(ValueError, match="snap_back"):
        m.update(ecm.PointState(), [0, 0, 0], 10.0, snap_back="jump")


def test_a_file_that_does_not_exist_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.yaml"):
        ecm.Material.from_file(tmp_path / "nope.yaml")


def test_numpy_scalars_are_numbers():
    # Issue: json refused np.int64 ("not JSON serializable"), update_many refused H = np.int64(10).
    as_numpy = dict(CONCRETE, youngs_modulus=np.int64(32000), poisson_ratio=np.float32(0.2),
                    softening_exponent=np.float64(0.128))
    m, reference = ecm.Material(**as_numpy), ecm.Material(**CONCRETE)
    assert m.to_yaml() == reference.to_yaml()  # float32(0.2) is read as 0.2, its shortest text
    for H in (np.int64(10), np.float32(10.0), 10):
        points = ecm.PointArray(2)
        out = m.update_many(points, np.full((2, 3), 1e-6), H)
        np.testing.assert_array_equal(out["stress"][0], reference.stiffness @ np.full(3, 1e-6))
    with pytest.raises(ValueError, match="H must be a number or an array"):
        m.update_many(ecm.PointArray(2), np.zeros((2, 3)), np.ones(3))


def test_states_out_of_range_are_refused():
    b = ecm.BandState()
    for field, value in (("integrity", -1.0), ("integrity", 0.0), ("integrity", 1.5), ("volume_fraction", 5.0),
                         ("volume_fraction", 1.0), ("volume_fraction", 0.0), ("crack_normal", [0.0, 0.0]),
                         ("crack_normal", [1.0, 1.0]), ("jump", [np.nan, 0.0]), ("onset_strain", [np.inf, 0, 0])):
        with pytest.raises(ValueError, match=field):
            setattr(b, field, value)
    with pytest.raises(ValueError, match="strain"):
        ecm.PointState([np.nan, 0.0, 0.0])
    p = ecm.PointState()
    with pytest.raises(ValueError, match="crack_normal"):
        p.band = ecm.BandState()  # a default band has no normal yet
    with pytest.raises(ValueError, match="integrity"):
        p.integrity = 2.0
    good = ecm.BandState()
    good.crack_normal, good.integrity, good.volume_fraction = [1.0, 0.0], 0.5, 0.005
    p.band = good
    assert p.band.integrity == 0.5


def test_the_effective_size_is_checked_before_the_update():
    m = ecm.Material(**CONCRETE)
    for H in (np.inf, np.nan, 0.0, -1.0):
        with pytest.raises(ValueError, match="effective size"):
            m.update(ecm.PointState(), [1e-6, 0, 0], H)
    # H below h (1 + 1e-6) = 0.05 mm: refused while intact too, as run_point refuses it
    with pytest.raises(ValueError, match="smallest effective size"):
        m.update(ecm.PointState(), [1e-6, 0, 0], 0.04)
    with pytest.raises(ValueError, match="smallest effective size"):
        m.update_many(ecm.PointArray(2), np.zeros((2, 3)), 0.04)
    with pytest.raises(ValueError, match="strain_increment"):
        m.update(ecm.PointState(), [np.nan, 0, 0], 10.0)


def test_point_arrays_take_negative_indices():
    m = ecm.Material(**CONCRETE)
    points = ecm.PointArray([ecm.PointState(), cracked_point(m)])
    assert points[-1].band is not None and points[-2].band is None
    points[-2] = points[-1]
    assert points[0].band.integrity == points[1].band.integrity
    with pytest.raises(IndexError):
        points[-3]
    with pytest.raises(IndexError):
        points[2]


def test_fields_say_their_units():
    assert "mm" in ecm.BandState.jump.__doc__ and "1 - D" in ecm.BandState.integrity.__doc__
    assert "h/H" in ecm.BandState.volume_fraction.__doc__
    assert "MPa" in ecm.UpdateResult.stress.__doc__ and "MPa" in ecm.UpdateResult.dissipation.__doc__
    assert "gamma_xy" in ecm.PointState.strain.__doc__ and "N, 3" in ecm.PointArray.__doc__
    for error in (ecm.InputError, ecm.ParameterError, ecm.CalibrationError, ecm.OutputError, ecm.CheckpointError):
        assert error.__doc__ and len(error.__doc__) > 40
    assert "mm" in ecm.read_mpm_output.__doc__ and "N" in ecm.read_mpm_output.__doc__


def test_the_snap_back_default_is_the_scenes_release():
    # One default for snap_back everywhere (material/snap_back_policy.hpp): release, as in the
    # YAML. H = 500 mm is above the paper concrete's snap-back size h (E + E_p) / E_p = 196 mm
    # (docs/model.md, identities): pulled in x, the point has no stable branch past its peak.
    m = ecm.Material(**CONCRETE)
    by_default, stopping = ecm.PointState(), ecm.PointState()
    released = stopped = False
    for _ in range(200):
        r = m.update(by_default, [1e-6, 0.0, 0.0], 500.0)
        assert r.converged
        released = released or r.released
        s = m.update(stopping, [1e-6, 0.0, 0.0], 500.0, snap_back="stop", check=False)
        if not s.converged:
            stopped = s.status == "snap-back"
            break
    assert released
    assert stopped


def test_a_failed_update_raises_with_its_status_unless_asked_for_the_status():
    """The snap-back of test_the_snap_back_default_is_the_scenes_release under snap_back="stop":
    by default ecm.UpdateFailed (a RuntimeError) with .status "snap-back" and the result, the
    state unchanged; check=False returns that result. update_many names its failed points."""
    m = ecm.Material(**CONCRETE)
    p = ecm.PointState()
    with pytest.raises(ecm.UpdateFailed) as caught:
        for _ in range(200):
            m.update(p, [1e-6, 0.0, 0.0], 500.0, snap_back="stop")
    assert caught.value.status == "snap-back" and not caught.value.result.converged
    before = p.strain.copy()
    r = m.update(p, [1e-6, 0.0, 0.0], 500.0, snap_back="stop", check=False)
    assert r.status == "snap-back" and np.array_equal(p.strain, before)
    points = ecm.PointArray(2)
    steps = np.array([[1e-6, 0.0, 0.0], [1e-7, 0.0, 0.0]])
    with pytest.raises(ecm.UpdateFailed, match="1 of 2 updates did not converge .first: point 0, snap-back."):
        for _ in range(200):
            m.update_many(points, steps, 500.0, snap_back="stop")


def test_a_strain_increment_of_the_wrong_shape_is_a_type_error_in_the_modules_words():
    m = ecm.Material(**CONCRETE)
    for wrong in ([1e-6, 0.0], [[1e-6, 0.0, 0.0]], "eps"):
        with pytest.raises(TypeError, match="strain_increment must be three numbers .eps_xx, eps_yy, gamma_xy."):
            m.update(ecm.PointState(), wrong, 10.0)


def test_help_on_material_lists_its_keys_with_units():
    doc = ecm.Material.__doc__
    for key, unit in (("youngs_modulus", "MPa"), ("band_width", "mm"), ("density", "t/mm^3"), ("fracture_energy", "N/mm")):
        line = next(l for l in doc.splitlines() if l.strip().startswith(key))
        assert unit in line, line


def test_update_takes_the_scenes_effective_size_key_and_the_former_h_warns():
    m = ecm.Material(**CONCRETE)
    a, b = ecm.PointState(), ecm.PointState()
    r = m.update(a, [1e-6, 0.0, 0.0], effective_size=10.0)
    with pytest.warns(DeprecationWarning, match="now effective_size"):
        s = m.update(b, [1e-6, 0.0, 0.0], H=10.0)
    assert np.array_equal(r.stress, s.stress)
    with pytest.raises(TypeError, match="needs effective_size"):
        m.update(ecm.PointState(), [1e-6, 0.0, 0.0])
