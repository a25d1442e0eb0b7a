"""A curvefold FOLD file's record is a claim, and ``check`` measures it: a catalogue.

A vault's shipped FOLD file is damaged, falsely recorded or benignly edited, each copy from
a seeded generator; plain ``check`` must fail every harmful copy, naming the check, and pass
every benign one. The rates are printed (``pytest -s``) and asserted.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from _cli import run
from curvefold.analysis._fold_record import chord_sagitta, sheet_count
from curvefold.analysis._foldcheck import check_fold
from curvefold.io import read_fold

SEED = 20261207


@pytest.fixture(scope="module")
def vault(tmp_path_factory):
    """A vault of three of the paper's tubes, as shipped (its FOLD file only), and its JSON."""
    out = tmp_path_factory.mktemp("record") / "vault"
    argv = ("vault", "--tubes", "3", "--samples", "401", "--formats", "fold", "--out", str(out))
    assert run(*argv).returncode == 0
    path = out / "vault.fold"
    return path, json.loads(path.read_text())


def _frames(doc):
    return doc["file_frames"]


def _frame_deleted(doc, rng):
    del _frames(doc)[int(rng.integers(1, len(_frames(doc))))]


def _frames_reversed(doc, rng):
    doc["file_frames"] = _frames(doc)[::-1]


def _frame_replaced_title_kept(doc, rng):
    i = int(rng.integers(1, len(_frames(doc)) - 1))
    title = _frames(doc)[i]["frame_title"]
    _frames(doc)[i] = dict(_frames(doc)[i + 1], frame_title=title)


def _seam_table_deleted(doc, rng):
    del doc["curvefold:seam_partners"]


def _bond_table_deleted(doc, rng):
    del doc["curvefold:bonds"]


def _one_seam_pair_deleted(doc, rng):
    del doc["curvefold:seam_partners"][int(rng.integers(len(doc["curvefold:seam_partners"])))]


def _stray_triangle(doc, rng):
    """Three new vertices, three boundary edges and a face, in every frame."""
    n = len(doc["vertices_coords"])
    for frame in [doc, *_frames(doc)]:
        x = np.array(frame["vertices_coords"])
        corner = x.max(axis=0) + 1.0
        tri = corner + np.eye(3, x.shape[1])[[0, 0, 1]] * [[0], [1], [1]]
        frame["vertices_coords"] = x.tolist() + tri.tolist()
        if "edges_foldAngle" in frame:
            frame["edges_foldAngle"] += [0.0, 0.0, 0.0]
    doc["edges_vertices"] += [[n, n + 1], [n + 1, n + 2], [n + 2, n]]
    doc["edges_assignment"] += ["B", "B", "B"]
    doc["edges_curvefold:kind"] += ["boundary"] * 3
    doc["faces_vertices"].append([n, n + 1, n + 2])
    doc["faces_curvefold:group"].append(doc["faces_curvefold:group"][-1])


def _unit_falsified(doc, rng):
    doc["frame_unit"] = "m"


def _units_falsified(doc, rng):
    doc["curvefold:design"]["design"]["output"]["units"] = str(rng.choice(["cm", "in", "m"]))


def _deviation_falsified(doc, rng):
    doc["curvefold:metadata"]["mesh_deviation"] = 1e-9


def _radius_falsified(doc, rng):
    doc["curvefold:metadata"]["radius"] = float(rng.choice([0.5, 2.0]))


def _stretch_falsified(doc, rng):
    doc["curvefold:metadata"]["mesh_stretch"] = 1e-7


def _tubes_falsified(doc, rng):
    doc["curvefold:metadata"]["tubes"] += int(rng.integers(1, 3))


def _design_angle_falsified(doc, rng):
    doc["curvefold:metadata"]["design_fold_angle_deg"] = 80.0


def _width_falsified(doc, rng):
    doc["curvefold:metadata"]["width"] *= 1.5


def _one_bond_pair_deleted(doc, rng):
    del doc["curvefold:bonds"][int(rng.integers(len(doc["curvefold:bonds"])))]


def _frame_scaled(doc, rng):
    frame = _frames(doc)[int(rng.integers(1, len(_frames(doc))))]
    frame["vertices_coords"] = (np.array(frame["vertices_coords"]) * 1.0005).tolist()


def _vertex_moved(doc, rng):
    frame = _frames(doc)[int(rng.integers(1, len(_frames(doc))))]
    x = np.array(frame["vertices_coords"])
    x[int(rng.integers(len(x)))] += 1e-6 * float(np.ptp(x, axis=0).max()) * rng.normal(size=3)
    frame["vertices_coords"] = x.tolist()


#: Harmful edits, each with a check that must fail.
HARMFUL = {
    "frame deleted": (_frame_deleted, "record"),
    "frames in reverse order": (_frames_reversed, "record"),
    "a frame replaced by the next, its title kept": (_frame_replaced_title_kept, "record"),
    "seam table deleted": (_seam_table_deleted, "record"),
    "bond table deleted": (_bond_table_deleted, "record"),
    "one seam pair deleted": (_one_seam_pair_deleted, "record"),
    "a stray disconnected triangle": (_stray_triangle, "record"),
    "frame_unit changed to m": (_unit_falsified, "record"),
    "the design's units changed": (_units_falsified, "record"),
    "mesh_deviation set to 1e-9": (_deviation_falsified, "record"),
    "radius changed": (_radius_falsified, "record"),
    "mesh_stretch falsified": (_stretch_falsified, "record"),
    "tubes falsified": (_tubes_falsified, "record"),
    "design angle falsified": (_design_angle_falsified, "record"),
    "width falsified": (_width_falsified, "record"),
    "one bond pair deleted": (_one_bond_pair_deleted, "record"),
    "a frame scaled by 1.0005": (_frame_scaled, "isometry"),
    "a vertex moved by 1e-6 of the size": (_vertex_moved, "fold_angles"),
}


def _indented(doc, rng):
    doc["__indent__"] = int(rng.integers(1, 4))


def _keys_reordered(doc, rng):
    keys = list(doc)
    rng.shuffle(keys)
    items = [(k, doc.pop(k)) for k in keys]
    doc.update(items)


def _creator_changed(doc, rng):
    doc["file_creator"] = "another editor"


def _unknown_key(doc, rng):
    doc["myTool:note"] = "opened and saved"


def _rounded(doc, rng):
    """Every coordinate and angle rounded to 6 decimals, as a spreadsheet might save them."""
    for frame in [doc, *_frames(doc)]:
        frame["vertices_coords"] = np.round(frame["vertices_coords"], 6).tolist()
        if "edges_foldAngle" in frame:
            frame["edges_foldAngle"] = np.round(frame["edges_foldAngle"], 6).tolist()


def _single_precision(doc, rng):
    """Every coordinate in single precision (float32), as a GPU tool keeps them."""
    for frame in [doc, *_frames(doc)]:
        x = np.asarray(frame["vertices_coords"], np.float32)
        frame["vertices_coords"] = x.astype(float).tolist()


def _edge_split(doc, rng, kind="ruling"):
    """A ruling (or crease) split at its midpoint in every frame: its two faces become quads
    whose fan triangle beside the new vertex has no area. (A glued edge split without its
    partner no longer meets it: not a benign edit.)"""
    glued = set(np.ravel(doc["curvefold:seam_partners"] + doc["curvefold:bonds"]).tolist())
    rulings = [e for e, k in enumerate(doc["edges_curvefold:kind"]) if k == kind and e not in glued]
    e = int(rng.choice(rulings))
    a, b = doc["edges_vertices"][e]
    m = len(doc["vertices_coords"])
    for frame in [doc, *_frames(doc)]:
        x = np.asarray(frame["vertices_coords"])
        frame["vertices_coords"] = x.tolist() + [((x[a] + x[b]) / 2).tolist()]
        if "edges_foldAngle" in frame:
            frame["edges_foldAngle"].append(frame["edges_foldAngle"][e])
    doc["edges_vertices"][e] = [a, m]
    doc["edges_vertices"].append([m, b])
    doc["edges_assignment"].append(doc["edges_assignment"][e])
    doc["edges_curvefold:kind"].append(kind)
    for face in doc["faces_vertices"]:
        for i in range(len(face)):
            if {face[i], face[(i + 1) % len(face)]} == {a, b}:
                face.insert(i + 1, m)
                break


def _turned_over(doc, rng):
    """The sheet seen from its other side: faces wound the other way, M and V swapped and every
    fold angle negated, the crease pattern mirrored in its plane."""
    x = np.asarray(doc["vertices_coords"], float)
    x[:, 0] *= -1
    doc["vertices_coords"] = x.tolist()
    doc["faces_vertices"] = [face[::-1] for face in doc["faces_vertices"]]
    doc["edges_assignment"] = [{"M": "V", "V": "M"}.get(a, a) for a in doc["edges_assignment"]]
    for frame in [doc, *_frames(doc)]:
        frame["edges_foldAngle"] = [-a for a in frame["edges_foldAngle"]]


#: Benign edits: the geometry and its record unchanged.
BENIGN = {
    "rounded to 6 decimals": _rounded,
    "a ruling split at its midpoint": _edge_split,
    "a crease split at its midpoint": lambda doc, rng: _edge_split(doc, rng, "fold"),
    "float32 coordinates": _single_precision,
    "indented": _indented,
    "keys reordered": _keys_reordered,
    "file_creator changed": _creator_changed,
    "an unknown key added": _unknown_key,
    "the sheet turned over": _turned_over,
}


def _copy(tmp_path, doc, edit, seed):
    doc = json.loads(json.dumps(doc))
    edit(doc, np.random.default_rng(seed))
    indent = doc.pop("__indent__", None)
    path = tmp_path / "copy.fold"
    path.write_text(json.dumps(doc, indent=indent))
    return path


def test_the_shipped_file_keeps_its_record(vault):
    path, _ = vault
    result = {c.name: c for c in check_fold(path).checks}
    assert result["record"].status == "pass"
    doc = read_fold(path)
    assert sheet_count(doc.crease_pattern) == 2 * doc.metadata["tubes"]
    # the recorded deviation is about the written chords' sagitta at the design angle
    design = doc.folded[doc.design["fold_angles"].index(90.0)][1]
    assert 0.5 < doc.metadata["mesh_deviation"] / chord_sagitta(design) < 1.5


@pytest.mark.parametrize("name", HARMFUL)
def test_a_harmful_copy_fails_a_named_check(tmp_path, vault, name):
    edit, check = HARMFUL[name]
    result = check_fold(_copy(tmp_path, vault[1], edit, SEED))
    failed = {c.name: c for c in result.checks if c.status == "fail"}
    assert check in failed, (name, {c.name: c.status for c in result.checks})
    assert failed[check].where


@pytest.mark.parametrize("name", BENIGN)
def test_a_benign_copy_passes(tmp_path, vault, name):
    result = check_fold(_copy(tmp_path, vault[1], BENIGN[name], SEED))
    assert result.ok, [(c.name, c.where) for c in result.checks if c.status == "fail"]
    if "split" in name:  # the vertex on a straight side is named, the tolerances unchanged
        planarity = {c.name: c for c in result.checks}["face_planarity"]
        assert "on a straight side of their polygon" in planarity.where
        shipped = {c.name: c.tolerance or 0.0 for c in check_fold(vault[0]).checks}
        # within the written precision of the new vertex (the midpoint has more digits)
        assert {c.name: c.tolerance or 0.0 for c in result.checks} == pytest.approx(
            shipped, rel=0.1
        )


def test_a_split_edge_hides_no_damage(tmp_path, vault):
    """A split edge's fan triangle with no area made the smallest triangle height 0, and every
    angle tolerance derived from it (face_planarity 1.8e8°): a bent face passed beside it."""

    def split_and_bent(doc, rng):
        _edge_split(doc, rng, "fold")
        _vertex_moved(doc, rng)
        frame = _frames(doc)[-1]
        x = np.array(frame["vertices_coords"])
        x[len(x) // 2] += 1e-3 * float(np.ptp(x, axis=0).max())
        frame["vertices_coords"] = x.tolist()

    result = check_fold(_copy(tmp_path, vault[1], split_and_bent, SEED))
    failed = {c.name for c in result.checks if c.status == "fail"}
    assert {"fold_angles", "face_planarity"} <= failed, failed


@pytest.mark.slow
def test_the_catalogue_rates(tmp_path, vault, capsys):
    """Every family over three seeds: harmful copies caught, benign ones passed."""
    caught = passed = 0
    for seed in range(3):
        for edit, _ in HARMFUL.values():
            caught += not check_fold(_copy(tmp_path, vault[1], edit, SEED + seed)).ok
        for edit in BENIGN.values():
            passed += check_fold(_copy(tmp_path, vault[1], edit, SEED + seed)).ok
    with capsys.disabled():
        print(
            f"\nplain check: {caught}/{3 * len(HARMFUL)} harmful copies fail, "
            f"{passed}/{3 * len(BENIGN)} benign copies pass"
        )
    assert caught == 3 * len(HARMFUL) and passed == 3 * len(BENIGN)


@pytest.mark.parametrize(
    "argv",
    [
        ("tube", "--panels", "4"),
        ("vault", "--tubes", "2", "--layers", "2", "--samples", "201"),
        ("block", "--samples", "201"),
    ],
    ids=["panel tube", "two-layer vault", "block"],
)
def test_shipped_files_of_every_kind_keep_their_record(tmp_path, argv):
    """Rigid panels fold their fold lines by their own angles; a layered vault has a tube per
    cell: neither is a false record."""
    out = tmp_path / "out"
    result = run(*argv, "--formats", "fold", "--out", str(out))
    assert result.returncode == 0, result.stdout
    report = json.loads((out / "report.json").read_text())
    assert report["certificate_file"]["ok"], report["certificate_file"]["checks"]


def _vertices_renumbered(doc, rng):
    order = rng.permutation(len(doc["vertices_coords"]))  # new vertex i is old order[i]
    new = np.argsort(order)  # old vertex v is new new[v]
    for frame in [doc, *_frames(doc)]:
        frame["vertices_coords"] = np.asarray(frame["vertices_coords"])[order].tolist()
    doc["edges_vertices"] = new[np.asarray(doc["edges_vertices"])].tolist()
    doc["faces_vertices"] = [[int(new[v]) for v in face] for face in doc["faces_vertices"]]


def _edges_renumbered(doc, rng):
    order = rng.permutation(len(doc["edges_vertices"]))
    new = np.argsort(order)
    for key in ("edges_vertices", "edges_assignment", "edges_curvefold:kind"):
        doc[key] = [doc[key][e] for e in order]
    for frame in [doc, *_frames(doc)]:
        if "edges_foldAngle" in frame:
            frame["edges_foldAngle"] = [frame["edges_foldAngle"][e] for e in order]
    for key in ("curvefold:seam_partners", "curvefold:bonds"):
        doc[key] = new[np.asarray(doc[key], np.int64).reshape(-1, 2)].tolist()


def _face_lists_rotated(doc, rng):
    doc["faces_vertices"] = [
        face[k:] + face[:k]
        for face, k in zip(doc["faces_vertices"], rng.integers(0, 3, len(doc["faces_vertices"])))
    ]


def _rigid_motion(doc, rng):
    """Every frame turned and moved (the crease pattern in its plane)."""
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.linalg.det(q))
    angle = rng.uniform(0, 2 * np.pi)
    plane = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    for frame in [doc, *_frames(doc)]:
        x = np.asarray(frame["vertices_coords"])
        turn = q if x.shape[1] == 3 else plane
        frame["vertices_coords"] = np.round(x @ turn.T + rng.normal(size=x.shape[1]), 12).tolist()


def _renumbered_and_moved(doc, rng):
    _vertices_renumbered(doc, rng)
    _edges_renumbered(doc, rng)
    _rigid_motion(doc, rng)


#: Benign under --rebuild too: the geometry's meaning is unchanged.
BENIGN_REBUILT = {
    "renumbered and moved": _renumbered_and_moved,
    "the sheet turned over and renumbered": lambda doc, rng: (
        _turned_over(doc, rng) or _vertices_renumbered(doc, rng)
    ),
    "a crease split at its midpoint": lambda doc, rng: _edge_split(doc, rng, "fold"),
    "vertices renumbered": _vertices_renumbered,
    "edges renumbered": _edges_renumbered,
    "face lists rotated": _face_lists_rotated,
    "every frame moved rigidly": _rigid_motion,
    "rounded to 6 decimals": _rounded,
    "float32 coordinates": _single_precision,
}


@pytest.mark.parametrize("name", BENIGN_REBUILT)
def test_rebuild_compares_what_the_geometry_means(tmp_path, vault, name):
    """It was an exact comparison of the arrays: each of these failed --rebuild."""
    path = _copy(tmp_path, vault[1], BENIGN_REBUILT[name], SEED)
    result = run("check", str(path), "--rebuild", "--json")
    checks = {c["name"]: c for c in json.loads(result.stdout)["checks"]}
    assert result.returncode == 0, [(n, c["where"]) for n, c in checks.items() if c["where"]]
    assert checks["rebuild"]["status"] == "pass"


def test_rebuild_fails_a_changed_design_and_a_moved_vertex(tmp_path, vault):
    def widened(doc, rng):
        doc["curvefold:design"]["design"]["vault"]["width"] = 0.081

    def split_off_its_line(doc, rng):
        _edge_split(doc, rng, "fold")
        frame = _frames(doc)[-1]
        frame["vertices_coords"][-1][2] += 1e-4

    for edit in (
        widened,
        split_off_its_line,
        _tubes_falsified,
        lambda d, rng: _turned_over(d, rng) or _vertex_moved(d, rng),
        _vertex_moved,
        lambda d, rng: _rigid_motion(d, rng) or _vertex_moved(d, rng),
    ):
        path = _copy(tmp_path, vault[1], edit, SEED)
        result = run("check", str(path), "--rebuild", "--json")
        checks = {c["name"]: c for c in json.loads(result.stdout)["checks"]}
        assert result.returncode == 1 and checks["rebuild"]["status"] == "fail"


def test_a_panel_frame_replaced_under_its_title_fails_the_record(tmp_path):
    """Rigid panels fold their crease by the frame's angle, the most of any fold edge (to 1e-9°
    measured on a 4-panel tube): a frame with another's coordinates passed."""
    out = tmp_path / "out"
    assert run("tube", "--panels", "4", "--formats", "fold", "--out", str(out)).returncode == 0
    doc = json.loads((out / "tube.fold").read_text())
    assert check_fold(out / "tube.fold").ok
    doc["file_frames"][3] = dict(doc["file_frames"][2], frame_title="fold angle 45°")
    path = tmp_path / "replaced.fold"
    path.write_text(json.dumps(doc))
    record = {c.name: c for c in check_fold(path).checks}["record"]
    assert record.status == "fail" and "folds its creases by 30°, the record 45°" in record.where


def test_a_panel_vault_moved_and_written_with_more_digits_keeps_its_record(tmp_path):
    """The 16-panel vault is written to 1e-12 of its size (11 decimals); moved rigidly and written
    to 12, its digits say 5e-13 while it still holds the first rounding: the stretch measured at
    its 90° frame, 3.2e-10 on a 0.038 edge, failed the recorded 2.1e-14."""
    out = tmp_path / "out"
    argv = ("vault", "--panels", "16", "--formats", "fold", "--out", str(out))
    assert run(*argv).returncode == 0
    doc = json.loads((out / "vault.fold").read_text())
    path = _copy(tmp_path, doc, _rigid_motion, SEED + 1)
    record = {c.name: c for c in check_fold(path).checks}["record"]
    assert record.status == "pass", record.where
    # a falsified stretch still fails
    doc["curvefold:metadata"]["mesh_stretch"] = 1e-7
    record = {c.name: c for c in check_fold(_copy(tmp_path, doc, _rigid_motion, SEED + 1)).checks}
    assert record["record"].status == "fail"
