"""The designer's JSON API on a real server bound to 127.0.0.1: answers, files, refusals, load."""

from __future__ import annotations

import base64
import io
import json
import re
import threading
import tomllib
import urllib.parse
import zipfile

import numpy as np
import pytest

from _cli import run
from _designer import get, get_json, need

pytest.importorskip("fastapi")
from curvefold.analysis import check_fold  # noqa: E402
from curvefold.app._design import KINDS, default_design, parse_design  # noqa: E402
from curvefold.app.designer import api, jobs, preview, server  # noqa: E402
from curvefold.geometry._structure import drawable  # noqa: E402
from curvefold.vault import Vault, VaultDesign  # noqa: E402

#: A light vault: the answers are the same functions at any sample count.
LIGHT = "samples=201&tubes=4"


@pytest.fixture(scope="module")
def url():
    with server.serving() as base:
        yield base


def test_vault_json_is_what_the_command_line_prints(url, tmp_path):
    status, answer = get_json(f"{url}api/vault?{LIGHT}&a=0.35")
    assert status == 200
    printed = run("vault", "--samples", "201", "--tubes", "4", "--a", "0.35", "--json")
    assert printed.returncode == 0
    expected = json.loads(printed.stdout)
    assert answer.keys() == expected.keys()
    for key in (
        "kappa0_s0",
        "proportion_change",
        "p_xz",
        "tubes",
        "max_tubes",
        "span",
        "rise",
        "certificate",
        "design",
    ):
        assert answer[key] == expected[key], key  # the same computation: equal to the last bit


@pytest.mark.parametrize("kind", ["vault", "tube", "block"])
def test_fold_files_pass_the_check(url, tmp_path, kind):
    status, kind_header, body = get(
        f"{url}api/{kind}.fold?samples=101" + ("&tubes=3" if kind == "vault" else "")
    )
    assert status == 200 and kind_header == "application/json"
    path = tmp_path / f"{kind}.fold"
    path.write_bytes(body)
    assert check_fold(path).ok
    assert run("check", str(path)).returncode == 0


def test_every_kind_answers_and_files_come_from_the_registry(url):
    for kind in KINDS:
        status, answer = get_json(
            f"{url}api/{kind}?samples=101" + ("&tubes=2" if kind == "vault" else "")
        )
        assert (
            status == 200
            and answer["kind"] == kind
            and all(c["passed"] for c in answer["certificate"])
        )
    status, media, body = get(f"{url}api/tube.svg?samples=51")  # two pages: zipped
    assert status == 200 and media == "application/zip"
    assert zipfile.ZipFile(io.BytesIO(body)).namelist() == [
        "tube-pattern-p1.svg",
        "tube-pattern-p2.svg",
    ]
    # a single fold's files come from the registry too
    status, media, body = get(f"{url}api/crease.glb?samples=101")
    assert status == 200 and media == "model/gltf-binary" and body[:4] == b"glTF"
    status, answer = get_json(f"{url}api/crease.gif")
    assert status == 422 and answer["error"].startswith(
        'download: "gif" is not written for a crease design'
    )
    # the STEP of thick panels: a smooth tube writes none, and says so
    status, answer = get_json(f"{url}api/tube.step?samples=51")
    assert status == 422 and answer["error"].startswith(
        "format 'step': this design writes no STEP (AP214) of thick panels (--thickness on rigid"
    ), answer
    status, schema = get_json(f"{url}api/schema")
    assert [f["name"] for f in schema["formats"]] == [
        name for name, f in api.FORMATS.items() if not f.optional
    ]
    assert {s["name"] for s in schema["sections"]["vault"]} == {
        "a",
        "p_xy",
        "width",
        "tubes",
        "fold_angle",
        "radius",
        "layers",
        "direction",
        "panels",
    }


def test_the_panels_control_builds_rigid_panels(url, tmp_path):
    """The schema gives vaults, tubes and blocks a panels control; a request with panels=16
    builds, certifies and writes rigid panels."""
    _, schema = get_json(f"{url}api/schema")
    assert [
        sec for sec, specs in schema["sections"].items() if "panels" in {s["name"] for s in specs}
    ] == ["vault", "curve"]
    panels = next(s for s in schema["sections"]["curve"] if s["name"] == "panels")
    # the slider's span, not 1 to 5
    assert panels["typical"] == {"lo": 0, "hi": 64, "lo_closed": True, "hi_closed": True}
    query = "samples=101&tubes=3&panels=16"
    status, answer = get_json(f"{url}api/vault?{query}")
    assert status == 200 and answer["design"]["panels"] == answer["panels"] == 16
    checks = {c["name"]: c["passed"] for c in answer["certificate"]}
    assert {
        "panel_isometry",
        "panel_planarity",
        "panel_ground_plane",
        "mechanism_dof",
        "mechanism_clearance",
    } <= set(checks)
    assert all(checks.values()) and [m["dof"] for m in answer["mechanism"]["states"][1:]] == [1, 1]
    status, _, body = get(f"{url}api/vault/preview?{query}")
    motion = json.loads(body)["motion"]
    # every vertex of the 10 lattice polylines
    assert status == 200 and motion["vertices"] == 17 * (3 * 3 + 1)
    status, _, body = get(f"{url}api/vault.fold?{query}")
    (tmp_path / "vault.fold").write_bytes(body)
    assert status == 200 and check_fold(tmp_path / "vault.fold").ok


def test_saved_toml_rebuilds_the_design(url, tmp_path):
    status, _, body = get(f"{url}api/vault.toml?{LIGHT}&span=3&rise=1.7&p_xz=1.2")
    assert status == 200
    saved = tmp_path / "saved.toml"
    saved.write_bytes(body)
    shown = json.loads(get(f"{url}api/vault/preview?{LIGHT}&span=3&rise=1.7&p_xz=1.2")[2])
    assert tomllib.loads(body.decode()) == shown["design"]
    printed = json.loads(run("vault", str(saved), "--json").stdout)
    assert {k: printed[k] for k in shown["numbers"] if k in printed} == {
        k: v for k, v in shown["numbers"].items() if k in printed
    }
    np.testing.assert_allclose(
        [printed["span"], printed["rise"], printed["p_xz"]], [3.0, 1.7, 1.2], rtol=1e-9
    )


@pytest.mark.parametrize("kind", KINDS)
def test_a_design_survives_its_query(kind):
    design = default_design(kind)
    assert api.request_design(kind, api.design_query(design)) == design
    assert parse_design(api.design_toml(design)) == design


def test_preview_holds_the_motion_the_vault_makes(url):
    status, _, body = get(f"{url}api/vault/preview?{LIGHT}")
    assert status == 200
    motion = json.loads(body)["motion"]
    positions = np.frombuffer(base64.b64decode(motion["positions"]), np.float32).reshape(
        motion["states"], motion["vertices"], 3
    )
    angles = np.array(motion["angles"])
    assert angles[0] == 0 and motion["design_angle"] in angles and np.all(np.diff(angles) > 0)
    assert motion["end"] == "first contact" and angles[-1] == preview.MAX_FOLD
    # the state at the design angle is the vault standing on the ground, to float32 rounding
    vault = Vault.from_design(VaultDesign(tubes=4, samples=preview.MOTION_SAMPLES))
    curves, _, _ = drawable(
        vault.structure,
        vault.vertices,
        segments=preview.PREVIEW_SEGMENTS,
        max_cells=preview.PREVIEW_CELLS,
    )
    k = int(np.flatnonzero(angles == motion["design_angle"])[0])
    size = float(np.abs(curves).max())
    assert np.abs(positions[k] - curves.reshape(-1, 3)).max() <= 4 * np.finfo(np.float32).eps * size
    # on the ground to the integrator's error at the motion's 41 samples (7e-12 of the size; sixth
    # order, so under 1e-13 at 97), far below the float32 positions' rounding (6e-8)
    assert motion["lift_off"][k] <= 1e-10 * size and motion["lift_off"][0] > 0.1 * size
    triangles = np.frombuffer(base64.b64decode(motion["triangles"]), np.uint32)
    assert triangles.max() < motion["vertices"] and set(motion["lines"]) == {"fold", "seam", "rim"}


def test_a_coarse_build_solves_no_second_arch(monkeypatch):
    """The design at fewer samples takes the arch root of its build at its own samples: the same
    vault bit for bit as one built anew, for a smooth and a panel vault, and one solve of Eq.
    (20) for both."""
    from curvefold.app._build import build
    from curvefold.vault import _assembly
    from curvefold.vault._arch import solve_symmetric_arch

    solves = []
    monkeypatch.setattr(
        _assembly, "solve_symmetric_arch", lambda a: solves.append(a) or solve_symmetric_arch(a)
    )
    # builds of this process's earlier tests would solve nothing
    api.caches()["built"].cache_clear()
    for values, coarse in (
        ({"vault": {"a": 0.3125}}, preview.MOTION_SAMPLES),
        ({"samples": 201, "vault": {"a": 0.3125, "panels": 8}}, 49),
    ):
        design = api.design_from_dict({"kind": "vault", **values})
        shown = api.built(design, samples=coarse)
        anew = build(design.overrides(samples=coarse))
        assert shown.design.samples == coarse and shown.vault.arch == anew.vault.arch
        assert np.array_equal(shown.vault.vertices, anew.vault.vertices)
    # one for the smooth vault's two builds, one for its build anew (panels: solve_panel_arch)
    assert solves == [0.3125, 0.3125]
    with pytest.raises(
        _assembly.InputError, match="the arch root given is for a = 0.2, not a = 0.3"
    ):
        _assembly.arch_crease(0.3, 0, 1.0, 90.0, 41, root=solve_symmetric_arch(0.2))


def test_the_answer_splices_its_base64_into_the_json():
    """Bytes (base64) go in as strings after encoding, NumPy numbers as floats; text that looks
    like the splice stays text."""
    answer = {
        "positions": b"QUJD",
        "n": np.int64(3),
        "title": 'a "quoted" 0',
        "lines": {"fold": b"AAAA", "rim": b""},
    }
    out = preview._json(answer)
    assert json.loads(out) == {
        "positions": "QUJD",
        "n": 3.0,
        "title": 'a "quoted" 0',
        "lines": {"fold": "AAAA", "rim": ""},
    }
    assert (
        out
        == json.dumps(
            {**answer, "positions": "QUJD", "n": 3.0, "lines": {"fold": "AAAA", "rim": ""}}
        ).encode()
    )


def test_the_fold_slider_stops_at_the_first_contact(url):
    status, answer = get_json(f"{url}api/vault/contact?{LIGHT}")
    assert status == 200 and answer == {
        "first_contact": Vault.from_design(VaultDesign(tubes=4, samples=201)).first_contact()
    }
    assert 100 < answer["first_contact"] < 179
    status, answer = get_json(f"{url}api/tube/contact")
    assert (
        status == 422
        and answer["error"] == "the first contact is searched for vaults, not for a tube"
    )


#: Requests a hostile or careless client might send: each gets one line and 422 (404 for a path),
#: never 500.
HOSTILE = [
    (
        "api/vault/preview?a=5",
        "a must be in [0, 1.2707093728) (no arch stands beyond it: Eq. "
        "(20) has no root next to π there), got 5.0",
        "a",
    ),
    ("api/vault/preview?a=nan", "a must be a finite number, got nan", "a"),
    ("api/vault/preview?a=1e999", "a must be a finite number, got inf", "a"),
    ("api/vault/preview?a=" + "9" * 5000, "a is longer than 2000 characters", "a"),
    ("api/vault/preview?a=0.3&a=0.4", "a is given twice", "a"),
    ("api/vault/preview?a=1.3", "a must be in [0, 1.2707093728) (no arch stands beyond it", "a"),
    ("api/vault/preview?width=0.5&tubes=3", "tubes must be ≤ 1", "tubes"),
    ("api/vault/preview?width=9", "width = 9 is past regression for the base tube", "width"),
    (
        "api/vault/preview?tubes=-1",
        'tubes must be an integer in [1, 1000] or "max", got -1',
        "tubes",
    ),
    (
        "api/vault/preview?samples=200000",
        "this job needs about 43.9 GiB of memory (200000 "
        "samples × 96 strips), more than the budget of 2.0 GiB (CURVEFOLD_MEMORY_BUDGET); "
        "lower samples (at most 87",
        "samples",
    ),
    ("api/vault/preview?span=3&radius=2", "give span or radius, not both", "span"),
    ("api/vault/preview?direction=%00", 'direction must be one of "+", "-"', "direction"),
    ("api/vault/preview?evil=1", "unknown parameter 'evil' for a vault", None),
    (
        "api/tube/preview?kappa=__import__('os')",
        "[curve] kappa: function '__import__' is not allowed",
        "kappa",
    ),
    (
        "api/tube/preview?kappa=sin(s)",
        "[curve] kappa must be finite and > 0 per model unit; at s = 0 it is 0",
        "kappa",
    ),
    ("api/tube/preview?kappa=" + "(" * 500 + "1" + ")" * 500, "[curve] kappa", "kappa"),
    ("api/block/preview?cells=[[0,0],[0,0]]", "cells[1] repeats cell [0, 0]", "cells"),
    ("api/block/preview?cells={}", "cells must be an array", "cells"),
    ("api/block/preview?cells=" + "[" * 1900, "cells must be an array", "cells"),
    (
        "api/crease/preview?alpha=45&beta_right=90",
        "give beta_right or alpha, not both",
        "beta_right",
    ),
    ("api/nope", "unknown kind 'nope'", None),
    ("api/vault.exe", "unknown file 'exe'", None),
    ("api/vault/domain.svg?page=A9", "page must be one of", "page"),
]


@pytest.mark.parametrize("path, message, key", HOSTILE)
def test_refusals_are_one_line(url, path, message, key):
    status, answer = get_json(url + path)
    assert status == 422, answer
    assert answer["error"].startswith(message) or message in answer["error"], answer["error"]
    assert "\n" not in answer["error"] and "Traceback" not in answer["error"]
    assert answer["key"] == key


def test_unknown_paths_are_404_and_bugs_are_one_line_500(url, monkeypatch):
    assert get(url + "api/vault/nothing")[0] == 404
    assert get(url + "../../etc/passwd")[0] == 404
    assert get(url + "static/../server.py")[0] == 404
    # a bug in the server, and one in a worker (a job the worker cannot read): one line each, never
    # a traceback
    real = jobs.plan
    monkeypatch.setattr(jobs, "plan", lambda *args, **kwargs: 1 / 0)
    status, answer = get_json(url + "api/vault/preview")
    assert status == 500 and answer["error"].startswith(
        "internal error: ZeroDivisionError: division by zero. This is a bug"
    )
    monkeypatch.setattr(
        jobs,
        "plan",
        lambda *args, **kwargs: jobs.Plan(
            "quick",
            ("preview", "{not a design", (), None, None),
            real("preview", "vault", []).estimate,
        ),
    )
    status, answer = get_json(url + "api/vault/preview?a=0.3001")
    assert status == 500 and answer["error"].startswith(
        "internal error: JSONDecodeError: Expecting property name enclosed in double quotes"
    )
    assert answer["error"].endswith(
        "This is a bug in curvefold 0.1.0; please report it with the request"
    )
    assert "\n" not in answer["error"] and "Traceback" not in answer["error"]


def test_concurrent_clients_see_their_own_designs_and_the_caches_stay_bounded(url):
    """A small load: 4 clients × 10 requests with designs of their own; every answer is its own
    request's design."""
    errors: list[str] = []

    def client(c: int) -> None:
        for r in range(10):
            a = round(0.05 + 0.01 * c + 0.001 * r, 6)
            status, _, body = get(f"{url}api/vault/preview?samples=101&tubes=3&a={a}")
            if status != 200 or json.loads(body)["numbers"]["a"] != a:
                errors.append(f"client {c} request {r}: {status}")

    threads = [threading.Thread(target=client, args=(c,)) for c in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    assert not errors and not any(t.is_alive() for t in threads)
    memory = url.designer.status()["memory"]
    # every reservation given back
    assert 0 < memory["answers"] <= server.ANSWER_CACHE and memory["reserved"] == 0


def test_the_command_says_what_is_missing(monkeypatch, tmp_path):
    monkeypatch.setattr(server, "VENDOR", tmp_path)
    result = run("designer", "--no-browser")
    assert result.returncode == 2
    assert result.stderr == (
        "curvefold: error: the designer's JavaScript is not built "
        "(three.module.js is missing from the package): run 'bash scripts/build-designer.sh' "
        "(it needs npm) in a curvefold checkout\n"
    )
    design = tmp_path / "csv.toml"
    (tmp_path / "k.csv").write_text("kappa\n1\n1.2\n", encoding="utf-8")
    design.write_text(
        'kind = "tube"\n[curve]\nkappa = {csv = "k.csv", column = "kappa"}\n', encoding="utf-8"
    )
    monkeypatch.undo()
    need(
        server.missing_bundle() is None,
        "the designer's JavaScript is not built (bash scripts/build-designer.sh)",
    )
    result = run("designer", str(design), "--no-browser")
    assert (
        result.returncode == 2
        and "[curve] kappa is a CSV column; the designer takes numbers and expressions in s"
        in result.stderr
    )


def test_a_taken_port_is_one_line():
    with server.serving() as base:
        port = urllib.parse.urlsplit(base).port
        result = run("designer", "--no-browser", "--port", str(port))
    assert result.returncode == 2 and result.stderr.startswith(
        f"curvefold: error: cannot serve on 127.0.0.1:{port}: "
    )
    result = run("designer", "--no-browser", "--port", "70000")
    assert (result.returncode, result.stderr) == (
        2,
        "curvefold: error: --port must be in [0, 65535], got 70000\n",
    )
    for flag, value, message in (
        ("--time-limit", "0", "time_limit must be in (0, 3600] seconds, got 0"),
        ("--workers", "0", "workers must be an integer in [1, 16], got 0"),
    ):
        result = run("designer", "--no-browser", flag, value)
        assert (result.returncode, result.stderr) == (
            2,
            f"curvefold: error: {flag} {value}: {message}\n",
        )


def test_pattern_pages_come_in_page_order_from_the_writer():
    """The crease pattern's pages as the writer returns them, page 1 first (no file names read
    back)."""
    cells = json.dumps([[0, 0], [0, 1], [1, 1], [1, 2], [2, 2], [2, 3]])
    design = api.request_design(
        "block", [("samples", "51"), ("page", "A5"), ("scale", "27"), ("cells", cells)]
    )
    pages = api.pattern_pages(design)
    count = len(pages)
    assert count >= 10  # p10 would sort before p2 by name
    assert [re.search(r"page (\d+) of (\d+)</title>", page).groups() for page in pages] == [
        (str(i), str(count)) for i in range(1, count + 1)
    ]


def test_the_design_under_load_is_what_curvefold_load_prints(url):
    """The mechanics route answers on the heavy lane, budgeted with the model, with the numbers
    of ``curvefold load --json``; a bad material value is a 422 naming its key."""
    query = f"{LIGHT}&material=aluminium&thickness=0.002&snow=0.5"
    assert jobs.plan("mechanics", "vault", urllib.parse.parse_qsl(query)).lane == "heavy"
    status, answer = get_json(f"{url}api/vault/mechanics?{query}")
    assert status == 200, answer
    printed = run(
        "load",
        "--samples",
        "201",
        "--tubes",
        "4",
        "--material",
        "aluminium",
        "--thickness",
        "0.002",
        "--snow",
        "0.5",
        "--json",
    )
    expected = json.loads(printed.stdout)
    for key in (
        "total_weight",
        "reactions",
        "max_displacement",
        "max_stress",
        "utilisation",
        "fold_mode_gap",
        "soft_modes",
        "buckling_factor",
        "modes",
        "frequencies",
        "reactions_by_end",
        "notes",
    ):
        # the same computation: equal to the last bit
        assert answer["numbers"][key] == expected[key], key
    assert set(answer["labels"]) <= set(answer["numbers"]) and answer["labels"]["fold_mode_gap"][
        0
    ].startswith("fold-mode gap")
    # without a material the route analyses the default one, as the command does
    assert (
        get_json(f"{url}api/tube/mechanics?samples=101")[1]["numbers"]["material"]
        == "polypropylene"
    )
    for path, message, key in [
        ("api/vault/mechanics?thickness=0", "thickness must be in (0, 1) m", "thickness"),
        (
            "api/vault/mechanics?poisson=0.5&youngs_modulus=1e9&density=900",
            "poisson must be in (-1, 0.5)",
            "poisson",
        ),
        ("api/crease/mechanics", "a single curved fold has no end sections to hold", None),
        ("api/vault/mechanics?samples=100001&tubes=9", "this job needs about", "samples"),
    ]:
        status, answer = get_json(url + path)
        assert status == 422 and message in answer["error"] and "\n" not in answer["error"], answer
        assert answer["key"] == key, answer


def test_the_collapse_controls_come_from_the_schema():
    """The load panel's checkbox and imperfection field are the ``[loads]`` keys of ``load
    --nonlinear``, the checkbox in the designer's words; the command line's label is kept."""
    from curvefold.mechanics import NONLINEAR

    loads = {s["name"]: s for s in api.schema()["sections"]["loads"]}
    assert loads["nonlinear"]["kind"] == "flag" and loads["nonlinear"]["default"] is False
    assert loads["nonlinear"]["label"] == "follow to collapse (large displacements)"
    assert NONLINEAR.label == "collapse analysis"
    assert loads["imperfection"]["range"] == {
        "lo": 0.0,
        "hi": 0.1,
        "lo_closed": True,
        "hi_closed": True,
    }
    request, _ = api.read_request("vault", {"nonlinear": "true", "imperfection": "0.005"})
    assert request.design.loads.nonlinear and request.design.loads.imperfection == 0.005
