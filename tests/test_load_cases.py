"""The load cases against closed forms: each case's resultant, the reactions that carry it,
its checks.

The closed forms: self-weight = ρ g t × the developed area; snow = s × the area seen from
above; snow on half the span = s × that half's area; a pressure normal to the sheets sums
to the pressure times the projected area in each direction on an open arch, and on a
tube open at its ends to the pressure on its two end sections (with them, the tube is
closed and the sum is zero); a point load is its force on its node. Each closed-form check
is also run on a damaged case (a wrong sign, a half left out) and must then fail.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from _mechanics import mesh_of
from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.kernel import InputError
from curvefold.mechanics import (
    LOAD_CASES,
    MATERIALS,
    BarHingeModel,
    HalfSnow,
    LoadCase,
    Loads,
    PointLoad,
    SelfWeight,
    Snow,
    StructureModel,
    Supports,
    Wind,
    ZonedWind,
    _cases,
    _surface,
    static_response,
)
from curvefold.mechanics._loads import G
from curvefold.vault import Vault

PP = MATERIALS["polypropylene"]
T = 1e-3
R, W = 1.5, 0.8  # the arch's radius and length, m


def arch(start: float, stop: float, segments: int = 15, rows: int = 4) -> BarHingeModel:
    """A cylindrical sheet of radius R about the y axis, from angle ``start`` to ``stop`` (from +x
    towards +z), W long in y.

    Its projected areas: on z = 0, R W (cos start − cos stop); on x = 0,
    R W (sin stop − sin start).
    An odd number of segments puts the crest inside a triangle, which snow on half the span cuts.
    """
    theta = np.linspace(start, stop, segments + 1)
    y = np.linspace(0.0, W, rows + 1)
    x = np.array([[R * np.cos(t), yy, R * np.sin(t)] for t in theta for yy in y])
    node = np.arange(len(x)).reshape(segments + 1, rows + 1)
    a, b, c, d = (
        node[:-1, :-1].ravel(),
        node[1:, :-1].ravel(),
        node[1:, 1:].ravel(),
        node[:-1, 1:].ravel(),
    )
    triangles = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    edges, counts = np.unique(
        np.sort(
            np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]),
            axis=1,
        ),
        axis=0,
        return_counts=True,
    )
    kinds = np.where(counts == 1, "boundary", "ruling")
    return BarHingeModel.from_mesh(mesh_of(x, triangles, edges, kinds), PP, T, crease_stiffness=1.0)


@pytest.fixture(scope="module")
def half_arch():
    return arch(0.0, np.pi)


@pytest.fixture(scope="module")
def vault():
    return StructureModel.from_state(
        Vault.from_design(a=0.3, p_xy=0.75, tubes=3, samples=101).structure.state(), PP, T
    )


@pytest.fixture(scope="module")
def tube():
    curve = SpaceCurve.from_curvature(
        lambda s: 1 + 0.3 * np.sin(s), lambda s: 0.2 + 0.3 * np.cos(s), 3.0, samples=41
    )
    lattice = Lattice.from_crease(Crease.from_curve(curve, fold_angle=90), 0.1, 0.08)
    return StructureModel.from_state(Structure.tube(lattice).state(), PP, T)


def resultant_error(case: LoadCase, model, expected) -> float:
    """|Σ f − expected| over |expected|: the closed-form check every case is held to."""
    total = case.forces(model).sum(axis=0)
    expected = np.asarray(expected, float)
    return float(np.linalg.norm(total - expected) / np.linalg.norm(expected))


def end_caps(sm: StructureModel) -> np.ndarray:
    """The vector areas (2K, 3) of every tube's end sections, pointing out of the tube."""
    x = sm.model.nodes[sm.end_sections()]  # (2K, 4, 3)
    vectors = 0.5 * np.cross(x, np.roll(x, -1, axis=1)).sum(axis=1)
    outward = np.sign(((x.mean(axis=1) - sm.model.nodes.mean(axis=0)) * vectors).sum(axis=1))
    return outward[:, None] * vectors


def test_the_registry_holds_every_case_by_its_name():
    assert list(LOAD_CASES) == ["self_weight", "snow", "snow_half", "wind", "wind_zones", "point"]
    for name, case in LOAD_CASES.items():
        assert case.name == name and issubclass(case, LoadCase) and case().describe()
        assert (
            LoadCase.from_dict(case().to_dict(), "") == case()
        )  # the design file's entry and back


def test_self_weight_is_the_density_the_thickness_and_g_times_the_developed_area(vault, half_arch):
    for model in (vault, half_arch):
        m = vault.model if model is vault else model
        expected = [0.0, 0.0, -PP.density * T * G * m.membrane_area.sum()]
        assert resultant_error(SelfWeight(), model, expected) < 1e-12


def test_snow_is_the_load_times_the_area_seen_from_above(half_arch):
    s = 700.0
    assert resultant_error(Snow(s), half_arch, [0, 0, -s * 2 * R * W]) < 1e-12
    assert (
        resultant_error(Snow(s), arch(0.0, np.pi / 2), [0, 0, -s * R * W]) < 1e-12
    )  # a quarter: R W from above


def test_snow_on_half_the_span_is_the_load_times_that_half_s_area(half_arch, monkeypatch):
    """The crest (x = 0) lies inside triangles: they are cut there, each part loading its
    corners."""
    s = 700.0
    for side in ("start", "end"):
        case = HalfSnow(s, side)
        assert resultant_error(case, half_arch, [0, 0, -s * R * W]) < 1e-12
        f = case.forces(half_arch)
        x = half_arch.nodes[:, 0]
        assert (
            np.abs(f[x * (1 if side == "end" else -1) < -0.2 * R]).max() == 0
        )  # nothing on the far half
    # damaged: a cut triangle's part left out (the crest's triangles dropped), or the whole
    # span loaded
    whole = _surface._clipped

    def drop_cut(xy, d):
        area, centroid = whole(xy, d)
        return np.where((d >= 0).all(axis=1), area, 0.0), centroid

    with monkeypatch.context() as m:
        m.setattr(_surface, "_clipped", drop_cut)
        assert resultant_error(HalfSnow(s), half_arch, [0, 0, -s * R * W]) > 1e-2
    assert resultant_error(Snow(s), half_arch, [0, 0, -s * R * W]) == pytest.approx(1.0)


def test_snow_on_half_a_vault_s_span_splits_its_snow_at_the_crown(vault):
    s = 500.0
    full = Snow(s).forces(vault)
    start, end = HalfSnow(s, "start").forces(vault), HalfSnow(s, "end").forces(vault)
    assert_allclose(
        start + end, full, atol=1e-12 * s
    )  # the two halves make the whole, node by node
    assert start[:, 2].sum() == pytest.approx(
        0.5 * full[:, 2].sum(), rel=1e-3
    )  # a symmetric vault: half each
    n = vault.state.vertices.shape[1]
    loaded = vault.node_sample[np.flatnonzero(start[:, 2])]
    assert (
        loaded.max() <= (n - 1) // 2 + 1 and loaded.min() == 0
    )  # the start half: from the foot t = 0 to the crown


def test_a_normal_pressure_on_an_arch_is_the_pressure_times_its_projected_areas(
    half_arch, monkeypatch
):
    q, cp = 600.0, -0.8
    w = cp * q  # suction: the arch is pulled out, up
    assert resultant_error(Wind(q, cp), half_arch, [0, 0, -w * 2 * R * W]) < 1e-12
    quarter = arch(0.0, np.pi / 2)
    assert (
        resultant_error(Wind(q, cp), quarter, [-w * R * W, 0, -w * R * W]) < 1e-12
    )  # seen from x and from z
    # damaged: the normals turned inward (a wrong sign)
    outward = _surface.face_vectors
    monkeypatch.setattr(
        _cases, "face_vectors", lambda model: (outward(model)[0], -outward(model)[1])
    )
    assert resultant_error(Wind(q, cp), quarter, [-w * R * W, 0, -w * R * W]) == pytest.approx(2.0)


def band(x: np.ndarray, z: np.ndarray, right: float, left: float) -> np.ndarray:
    """The vector area of an arch's polygon (nodes x, z by angle) between x = right and x = left
    (its outward normals): W (Δz, 0, −Δx) from the point at ``right`` to the one at ``left``."""
    order = np.argsort(x)
    zr, zl = np.interp([right, left], x[order], z[order])
    return W * np.array([zl - zr, 0.0, -(left - right)])


def test_wind_in_en_zones_is_each_zone_s_pressure_times_its_projected_areas(monkeypatch):
    """16 segments: the zones' borders x = ±R/2 cut triangles; each zone's resultant is its
    pressure times the vector area of its band of the polygon."""
    sheet = arch(0.0, np.pi, segments=16)
    section = sheet.nodes[sheet.nodes[:, 1] == 0]
    x, z = section[:, 0], section[:, 2]
    q, cp = 500.0, (-0.5, -1.1, -0.4)
    expected = {}
    for windward, (a, c) in (("start", (-R, R)), ("end", (R, -R))):
        borders = np.linspace(a, c, 5)[[0, 1, 3, 4]]  # the span's quarters from the windward edge
        bands = [
            band(x, z, *sorted(pair, reverse=True))
            for pair in (
                (borders[0], borders[1]),
                (borders[1], borders[2]),
                (borders[2], borders[3]),
            )
        ]
        expected[windward] = -q * sum(k * b for k, b in zip(cp, bands))
        assert resultant_error(ZonedWind(q, *cp, windward), sheet, expected[windward]) < 1e-12
    assert not np.allclose(expected["start"], expected["end"])  # the windward side matters
    # one coefficient everywhere: the uniform wind's
    uniform = ZonedWind(q, -0.7, -0.7, -0.7).forces(sheet)
    assert_allclose(uniform, Wind(q, -0.7).forces(sheet), rtol=0, atol=1e-12 * q)

    # damaged: the zones taken by the triangles' centroids (the cut triangles wholly in one zone)
    def by_centroid(d):
        return np.where(d.mean(axis=1) >= 0, 1 / 3, 0.0)[:, None] * np.ones(3)

    monkeypatch.setattr(_cases, "beyond_shares", by_centroid)
    assert resultant_error(ZonedWind(q, *cp), sheet, expected["start"]) > 1e-3


def test_a_normal_pressure_on_a_tube_closed_by_its_end_sections_sums_to_zero(tube, vault):
    """A tube is open at its end sections: the pressure on its sheets is the pressure on the two
    ends it lacks, turned. Between bonded tubes the faces press on each other and cancel: the
    vault sums to its ends too."""
    q = 400.0
    for sm in (tube, vault):
        f = Wind(q).forces(sm).sum(axis=0)
        caps = end_caps(sm).sum(axis=0)
        scale = q * sm.model.membrane_area.sum()
        assert np.linalg.norm(f - q * caps) < 1e-12 * scale
        assert (
            np.linalg.norm(caps) > 1e-3 * sm.model.membrane_area.sum()
        )  # the check is not of nothing


def test_a_point_load_is_its_force_on_the_nearest_node(vault):
    at = vault.model.nodes[123] + [0.01, -0.02, 0.01]
    f = PointLoad(250.0, tuple(at)).forces(vault)
    assert_allclose(f.sum(axis=0), [0, 0, -250.0], rtol=0, atol=0) and np.count_nonzero(
        f
    ) == 1 and f[123, 2] == -250.0
    reach = 0.05 * vault.model.size
    with pytest.raises(
        InputError,
        match=rf"^point load at \[0, 1, -1\] m is .* m from the structure's nearest node, "
        rf"farther than the {reach:.3g} m allowed \(5% of its size, {vault.model.size:.3g} m\)$",
    ):
        PointLoad(1.0, (0.0, 1.0, -1.0)).forces(vault)


@pytest.mark.parametrize(
    "case",
    [
        SelfWeight(),
        Snow(500.0),
        HalfSnow(500.0, "start"),
        Wind(600.0, -0.8),
        ZonedWind(600.0, 0.3, -1.0, -0.4),
        PointLoad(80.0),
    ],
    ids=lambda c: c.name,
)
def test_the_supports_carry_each_case_equal_and_opposite(vault, case):
    result, _ = static_response(vault.model, Loads((case,)).forces(vault), Supports().fixed(vault))
    f = case.forces(vault)
    assert_allclose(result.total_load, f.sum(axis=0), rtol=0, atol=1e-12 * np.abs(f).sum())
    assert np.linalg.norm(result.total_reaction + result.total_load) <= 1e-12 * np.abs(f).sum()
    assert result.max_displacement > 0


def test_loads_sum_their_cases_and_the_usual_keywords_make_them(vault):
    cases = (SelfWeight(), Snow(300.0), PointLoad(20.0))
    assert_allclose(Loads(cases).forces(vault), sum(c.forces(vault) for c in cases), rtol=0, atol=0)
    assert Loads.from_values(snow=300.0, point=20.0) == Loads(cases)
    assert Loads.from_values(self_weight=False).cases == ()
    assert Loads(cases).describe() == "self-weight + snow 0.3 kPa + 20 N at the apex"


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (
            lambda: Snow(-1.0),
            r"^snow load must be in \[0, 1000000\] Pa "
            r"\(a roof's snow is below 10 kPa; 1000 kPa is a press\), got -1\.0$",
        ),
        (
            lambda: HalfSnow(100.0, "middle"),
            r'^snow_half side must be one of "start", "end", got string \'middle\'$',
        ),
        (
            lambda: Wind(-5.0),
            r"^wind velocity_pressure must be in \[0, 100000\] Pa "
            r"\(a hurricane's is below 5 kPa\), got -5\.0$",
        ),
        (
            lambda: Wind(500.0, 4),
            r"^wind cp must be in \[-3, 3\] "
            r"\(EN 1991-1-4's coefficients lie within ±3\), got 4\.0$",
        ),
        (
            lambda: PointLoad(1e10),
            r"^point force must be in \[0, 1000000000\] N \(numerical range\), got 10000000000\.0$",
        ),
        (
            lambda: PointLoad(1.0, (0.0, 1.0)),
            r"^point at must be a point \[x, y, z\] in m, got array \(0\.0, 1\.0\)$",
        ),
        (
            lambda: PointLoad(1.0, (0.0, float("nan"), 1.0)),
            r"^point at\[1\] must be a finite number, got nan$",
        ),
        (
            lambda: LoadCase.from_dict(
                {"type": "snow", "load": 2000}, "design.toml: [[loads.case]] 1: "
            ),
            r"^design\.toml: \[\[loads\.case\]\] 1: snow load must be in \[0, 1000\] kPa "
            r"\(a roof's snow is below 10 kPa; "
            r"1000 kPa is a press\), got 2000\.0$",
        ),
        (
            lambda: LoadCase.from_dict(
                {"type": "wind", "speed": 30}, "design.toml: [[loads.case]] 2: "
            ),
            r"^design\.toml: \[\[loads\.case\]\] 2: unknown key 'speed' for type 'wind' "
            r"\(allowed: velocity_pressure, cp\)$",
        ),
        (
            lambda: Loads((Snow(1.0), "wind")),
            r"^loads must be load cases \(Snow\(500\.0\), …\), got string 'wind'$",
        ),
    ],
)
def test_each_check_names_the_value_and_its_range(make, match):
    with pytest.raises(InputError, match=match):
        make()


def test_snow_and_wind_need_a_sheet():
    bar = BarHingeModel(
        np.array([[0.0, 0, 0], [1, 0, 0]]), [[0, 1]], [1.0], np.zeros((0, 4), int), [], np.ones(2)
    )
    for case, what in ((Snow(1.0), "snow"), (HalfSnow(1.0), "snow"), (Wind(1.0), "wind")):
        with pytest.raises(
            InputError, match=rf"^{what} needs a sheet \(membrane triangles\) to fall on$"
        ):
            case.forces(bar)
