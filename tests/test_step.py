"""The thick panels' STEP file (curvefold.io._step), read back by OpenCascade's own STEP reader
(STEPControl_Reader, STEPCAFControl_Reader for the names): a valid closed solid per panel,
named as in the cut list, of the panel's volume and in the stated units; a damaged solid fails
the check.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

OCP = pytest.importorskip("OCP", reason="the STEP writer needs OCP: pip install 'curvefold[step]'")

from OCP.Bnd import Bnd_Box  # noqa: E402
from OCP.BRepBndLib import BRepBndLib  # noqa: E402
from OCP.BRepGProp import BRepGProp  # noqa: E402
from OCP.GProp import GProp_GProps  # noqa: E402
from OCP.IFSelect import IFSelect_RetDone  # noqa: E402
from OCP.STEPControl import STEPControl_Reader  # noqa: E402
from OCP.TopAbs import TopAbs_FACE, TopAbs_SOLID  # noqa: E402
from OCP.TopExp import TopExp_Explorer  # noqa: E402

from curvefold import InputError, Structure  # noqa: E402
from curvefold.geometry import PanelLattice, ThickPanels  # noqa: E402
from curvefold.geometry._lattice import _example_lattice  # noqa: E402
from curvefold.io._step import _faces, _solid, check_solid, write_thick_step  # noqa: E402

T = 0.01  # a 1 cm sheet on the example tube, model units (metres)


@pytest.fixture(scope="module")
def thick():
    return ThickPanels.offset(Structure.tube(PanelLattice.from_lattice(_example_lattice(), 4)), T)


def _volumes(thick, fold_angle=None):
    """Every solid's volume by the divergence theorem on its closed triangles (F,)."""
    x, tri = thick.triangles(fold_angle)
    a, b, c = (x[tri[:, i]] for i in range(3))
    signed = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    return signed.reshape(len(thick.side), -1).sum(axis=1)


def _solids(path):
    """The solids of a STEP file, as OpenCascade's reader reads them (in millimetres, its
    default ``xstep.cascade.unit``)."""
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    found = TopExp_Explorer(reader.OneShape(), TopAbs_SOLID)
    out = []
    while found.More():
        out.append(found.Current())
        found.Next()
    return out


def _volume(shape):
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def _names(path):
    """The names of a STEP file's products, as OpenCascade's reader decodes them."""
    from OCP.StepBasic import StepBasic_Product

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    model, kind = reader.StepModel(), StepBasic_Product.get_type_descriptor_s()
    entities = (model.Value(i) for i in range(1, model.NbEntities() + 1))
    return [e.Name().ToCString() for e in entities if e.IsKind(kind)]


def test_every_panel_is_a_valid_closed_solid_of_its_volume_read_back(thick, tmp_path):
    path = write_thick_step(tmp_path / "s.step", thick, unit="m", to_unit="mm")
    solids = _solids(path)
    assert len(solids) == len(thick.side) == 16
    assert [check_solid(s) for s in solids] == [None] * 16
    # the file is in millimetres and the reader's default unit too: volumes in mm³
    read = np.array([_volume(s) for s in solids]) * 1e-9
    expected = _volumes(thick)
    assert np.abs(read / expected - 1).max() < 1e-9  # measured 1.5e-14
    # every panel a prism: k + 2 planar faces
    k = thick.local.shape[1] // 2
    for s in solids:
        faces, found = 0, TopExp_Explorer(s, TopAbs_FACE)
        while found.More():
            faces, _ = faces + 1, found.Next()
        assert faces == k + 2


def test_the_bounding_box_is_the_stls(thick, tmp_path):
    path = write_thick_step(tmp_path / "s.step", thick, unit="m", to_unit="mm")
    box = Bnd_Box()
    for s in _solids(path):
        BRepBndLib.AddOptimal_s(s, box, False, False)
    lo, hi = np.array(box.CornerMin().Coord()), np.array(box.CornerMax().Coord())
    x, _ = thick.triangles()  # the STL's vertices (curvefold.io.write_thick_stl), in mm
    size = np.ptp(x, axis=0).max() * 1e3
    assert np.abs(lo - x.min(axis=0) * 1e3).max() < 1e-9 * size
    assert np.abs(hi - x.max(axis=0) * 1e3).max() < 1e-9 * size


def test_the_solids_are_named_by_the_cut_lists_panel_ids_in_ascii(thick, tmp_path):
    path = write_thick_step(tmp_path / "s.step", thick, unit="m", to_unit="mm")
    assert _names(path) == list(thick.labels())
    assert [row["panel"] for row in thick.cut_list()] == [thick.labels()[f] for f in thick.order]
    path.read_text(encoding="ascii")  # ISO 10303-21: the middle dots as \X2\00B7\X0\
    dot = " \\X2\\00B7\\X0\\ "
    assert f"PRODUCT('tube 1{dot}sheet A{dot}strip 1{dot}panel 1'" in path.read_text()


@pytest.mark.parametrize(
    ("to_unit", "stated", "mm"),
    [
        ("mm", "SI_UNIT(.MILLI.,.METRE.)", 1e3),
        ("m", "SI_UNIT($,.METRE.)", 1e3),
        ("in", "'INCH'", 1e3),
    ],
)
def test_the_file_states_its_unit_and_a_reader_scales_by_it(thick, tmp_path, to_unit, stated, mm):
    """Whatever the file's unit, the reader (in mm) finds the same solids: the unit is stated."""
    path = write_thick_step(tmp_path / f"s-{to_unit}.step", thick, unit="m", to_unit=to_unit)
    assert stated in path.read_text()
    read = np.array([_volume(s) for s in _solids(path)]) / mm**3
    assert np.abs(read / _volumes(thick) - 1).max() < 1e-9


def test_the_solids_follow_the_fold_angle(thick, tmp_path):
    flat = write_thick_step(tmp_path / "flat.step", thick, 0.0, unit="m", to_unit="mm")
    solids = _solids(flat)
    assert [check_solid(s) for s in solids] == [None] * 16
    read = np.array([_volume(s) for s in solids]) * 1e-9
    assert np.abs(read / _volumes(thick, 0.0) - 1).max() < 1e-9
    box = Bnd_Box()
    for s in solids:
        BRepBndLib.AddOptimal_s(s, box, False, False)
    x, _ = thick.triangles(0.0)
    assert np.allclose(box.CornerMax().Coord(), x.max(axis=0) * 1e3, rtol=0, atol=1e-9)


def test_a_solid_without_a_face_is_not_closed_and_fails_the_check(thick):
    k = thick.local.shape[1] // 2
    vertices = thick.triangles()[0][: 2 * k] * 1e3
    faces = _faces(k, True)
    assert check_solid(_solid(vertices, faces)) is None
    why = check_solid(_solid(vertices, faces[:-1]))  # a side face removed
    assert why is not None and ("not closed" in why or "not valid" in why), why
    # a face turned inside out: the sewing turns it back, the solid stays closed and valid
    turned = [*faces[:-1], faces[-1][::-1]]
    assert check_solid(_solid(vertices, turned)) is None
    # a corner moved off its face's plane: that face is no plane, the solid not closed
    bent = vertices.copy()
    bent[k] += [0.0, 0.0, 0.5]
    assert check_solid(_solid(bent, faces)) is not None


def test_the_writer_refuses_a_solid_that_fails_naming_its_panel(thick, tmp_path, monkeypatch):
    import curvefold.io._step as step

    monkeypatch.setattr(step, "_faces", lambda k, ccw: _faces(k, ccw)[:-1])
    with pytest.raises(
        RuntimeError, match=r"the solid of tube 1 · sheet A · strip 1 · panel 1 is "
    ):
        write_thick_step(tmp_path / "s.step", thick)
    assert not (tmp_path / "s.step").exists()


def test_a_unit_a_step_file_cannot_state_is_refused_with_the_allowed_ones(thick, tmp_path):
    with pytest.raises(InputError, match=r"to_unit must be one of mm, cm, m, in, .*got 'pt'"):
        write_thick_step(tmp_path / "s.step", thick, unit="m", to_unit="pt")


# -- the output folder: written for thick panels only, left out with a note without OCP
# --------------------------------------------------------------------------------------------

TUBE = ("tube", "--panels", "8", "--thickness", "0.002", "--formats", "stl,step", "--json")


def test_a_thick_tubes_folder_holds_its_step_solids_as_its_stl_in_mm(tmp_path):
    from _cli import run
    from curvefold.app._build import build
    from curvefold.app._design import default_design

    r = run(*TUBE, "--out", "t", cwd=tmp_path)
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert "notes" not in json.loads(r.stdout)
    folder = tmp_path / "t"
    assert {"tube_solids.step", "tube_solids.stl"} <= {p.name for p in folder.iterdir()}
    thick = build(default_design("tube").overrides(panels=8)).structure
    thick = ThickPanels.offset(thick, 0.002)
    solids = _solids(folder / "tube_solids.step")
    assert len(solids) == len(thick.side) and [check_solid(s) for s in solids] == [None] * len(
        solids
    )
    read = np.array([_volume(s) for s in solids]) * 1e-9  # mm³, the output's default units
    assert np.abs(read / _volumes(thick) - 1).max() < 1e-9
    # the STL's bounding box (float32, mm)
    data = (folder / "tube_solids.stl").read_bytes()
    records = np.frombuffer(
        data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    )
    stl = records["v"].reshape(-1, 3).astype(float)
    box = Bnd_Box()
    for s in solids:
        BRepBndLib.AddOptimal_s(s, box, False, False)
    size = np.ptp(stl, axis=0).max()
    assert np.abs(np.array(box.CornerMin().Coord()) - stl.min(axis=0)).max() < 1e-6 * size
    assert np.abs(np.array(box.CornerMax().Coord()) - stl.max(axis=0)).max() < 1e-6 * size
    assert _names(folder / "tube_solids.step") == list(thick.labels())
    # a structure without thick panels writes no STEP, and says nothing of it
    r = run("tube", "--panels", "8", "--formats", "step", "--json", "--out", "z", cwd=tmp_path)
    assert r.returncode in (0, 1) and "notes" not in json.loads(r.stdout), r.stderr
    assert not list((tmp_path / "z").glob("*.step"))


_WITHOUT_OCP = "import sys; sys.modules['OCP'] = None; from curvefold.app.cli import run; run()"


def test_without_ocp_the_step_file_is_left_out_with_one_line_naming_the_extra(tmp_path):
    r = subprocess.run(
        [sys.executable, "-c", _WITHOUT_OCP, *TUBE, "--out", "t"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=600,
    )
    assert r.returncode == 0 and r.stderr == "", r.stderr
    note = "step left out (it needs OCP: pip install 'curvefold[step]')"
    assert json.loads(r.stdout)["notes"] == [note]
    names = {p.name for p in (tmp_path / "t").iterdir()}
    assert "tube_solids.stl" in names and not [n for n in names if n.endswith(".step")]
    assert json.loads((tmp_path / "t" / "report.json").read_text())["notes"] == [note]


def test_a_single_crease_refuses_the_step_format_in_one_line(tmp_path):
    from _cli import run

    r = run("crease", "--samples", "41", "--formats", "step", "--out", "c", cwd=tmp_path)
    assert r.returncode == 2 and len(r.stderr.splitlines()) == 1, r.stderr
    assert r.stderr.strip().endswith(
        '"step" is not written for a crease design: the STEP file of thick panels is written '
        "for vault, tube and block designs"
    ), r.stderr
    assert not (tmp_path / "c").exists()


def test_the_memory_budget_counts_the_step_job_for_thick_panels_only():
    from curvefold.app import _budget as budget
    from curvefold.app._design import default_design

    panels = default_design("tube").overrides(panels=8)
    thick = panels.overrides(material={"material": "plywood", "thickness": 0.002})
    smooth = default_design("tube").overrides(material={"material": "plywood"})
    assert "solids" in budget._parts(thick, True)
    assert "solids" not in budget._parts(panels, True) + budget._parts(smooth, True)
