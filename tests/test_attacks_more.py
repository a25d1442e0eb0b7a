"""More hostile cases: memory a small file asks for, work the estimate did not see, values
inside the accepted ranges that broke the solvers (see ``test_attacks.py`` for the promise)."""

from __future__ import annotations

import json
import time
import tracemalloc

import pytest

from _cli import run
from test_attacks import refused


def _ragged(n: int, frames: int = 0) -> dict:
    """One face of ``n`` vertices and ``n - 2`` triangles on the same vertices: the faces hold
    ``4n - 6`` indices, a table padded to the longest face ``n(n - 1)``."""
    faces = [list(range(n))] + [[i, i + 1, i + 2] for i in range(n - 2)]
    return {
        "file_spec": 1.1,
        "vertices_coords": [[i % 100, i // 100] for i in range(n)],
        "edges_vertices": [[i, (i + 1) % n] for i in range(n)],
        "faces_vertices": faces,
        "file_frames": [{"frame_inherit": True, "frame_parent": 0}] * frames,
    }


@pytest.mark.parametrize("command", ["check", "mechanism"])
def test_faces_of_differing_lengths_are_not_padded_past_what_the_file_holds(tmp_path, command):
    # 84 kB: padded to its 2200-vertex face the table held 4.8 million indices, and a check
    # took 480 MB at once (2.4 GB with folded frames); now refused before the table exists
    text = json.dumps(_ragged(2200, frames=1), separators=(",", ":"))
    assert 80_000 < len(text) < 90_000
    (tmp_path / "f.fold").write_text(text)
    tracemalloc.start()
    start = time.perf_counter()
    try:
        r = run(command, "f.fold", cwd=tmp_path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert time.perf_counter() - start < 5
    assert peak < 40 * len(text)  # the parsed JSON's lists, about 20 bytes per byte
    refused(
        r,
        r"f\.fold \(key frame\): faces_vertices\[0\] has 2200 vertices: its 2199 faces padded "
        r"to it would hold 4837800 indices, more than the 1048576 curvefold reads \(4 times the "
        r"8794 they hold, at least 1048576\); split that face$",
    )


def test_a_long_face_beside_triangles_within_the_bound_is_read(tmp_path):
    from curvefold.io._fold_reading import read_fold

    (tmp_path / "f.fold").write_text(json.dumps(_ragged(1000)))  # 998 000 indices padded
    faces = read_fold(tmp_path / "f.fold").crease_pattern.faces_vertices
    assert faces.shape == (999, 1000)
    assert (faces[1:, 3:] == -1).all() and (faces[0] == range(1000)).all()
