"""Model: analyze() against `quadtri analyze --json`, tessellate() and patches() against
`quadtri convert`, evaluation at the corners."""

import json
import math
import re

import numpy as np
import pytest

import quadtri

LINES = 20000  # random lines per crack rate: enough to exercise it, quick on two cores


def same_metrics(py, cli):
    """Every key of the CLI's JSON, in its order, with the same value (convert_seconds is a
    wall time: only its type is compared)."""
    assert list(py) == list(cli)
    for key in cli:
        if key == "convert_seconds":
            assert isinstance(py[key], float) and py[key] >= 0
        else:
            assert py[key] == cli[key], (py["model"], key, py[key], cli[key])


def test_analyze_matches_the_cli_on_a_builtin_shape_for_every_model(cli):
    spec = "icosphere:1"
    expected = cli.json("analyze", spec, "--model", "all", "--json", "--lines", LINES)["models"]
    V, F, N, truth = quadtri.load_mesh(spec, truth=True)
    assert [m["model"] for m in expected] == quadtri.model_names()
    for want in expected:
        m = quadtri.Model(want["model"], V, F, N)
        got = m.analyze(lines=LINES, seed=1, truth=truth, mesh_name=spec)
        same_metrics(got, want)


@pytest.mark.parametrize("model", ["quadric-implicit-robust", "nagata", "shading"])
def test_analyze_matches_the_cli_on_a_file(cli, repo, model):
    path = repo / "scenes/meshes/torus.obj"
    want = cli.json("analyze", path, "--model", model, "--json", "--lines", LINES, "--seed", 7,
                    "--tessellation", 4)
    # split=True keeps the file's layout of normals exactly, as the CLI holds it.
    V, F, N, NI = quadtri.load_mesh(path, split=True)
    got = quadtri.Model(model, V, F, N, NI, tessellation=4).analyze(lines=LINES, seed=7,
                                                                     mesh_name=str(path))
    same_metrics(got, want)
    assert got["truth_distance"] is None and got["crack_rate"] is not None
    # One normal per vertex: the same surface and metrics, but the input triangles' render
    # geometry no longer stores normal indices of its own (the file indexes its normals apart).
    per_vertex = quadtri.Model(model, *quadtri.load_mesh(path), tessellation=4).analyze(
        lines=LINES, seed=7, mesh_name=str(path))
    for key in want:
        if key not in ("convert_seconds", "memory_bytes"):
            assert per_vertex[key] == want[key], key
    if model != "shading":
        assert per_vertex["memory_bytes"] == want["memory_bytes"]


def test_analyze_with_average_normals_matches_the_cli(cli):
    want = cli.json("analyze", "torus:1,0.35,16,8", "--model", "pn", "--json", "--lines", LINES,
                    "--normals", "average")
    V, F, N, truth = quadtri.load_mesh("torus:1,0.35,16,8", normals="average", truth=True)
    got = quadtri.Model("pn", V, F, N).analyze(lines=LINES, truth=truth,
                                               mesh_name="torus:1,0.35,16,8")
    same_metrics(got, want)


def test_truth_distance_is_analyzes():
    V, F, N, truth = quadtri.shape("ellipsoid", level=1, truth=True)
    m = quadtri.Model("quadric-param", V, F, N)
    d = m.truth_distance(truth)
    assert d == m.analyze(lines=100, truth=truth)["truth_distance"]
    assert 0 < d < 0.05
    robust = quadtri.Model("quadric-implicit-robust", *quadtri.shape("icosphere", level=2))
    assert robust.truth_distance(quadtri.Surface("sphere")) < 1e-9


def test_model_properties():
    V, F, N = quadtri.shape("icosahedron")
    m = quadtri.Model("quadric-implicit-robust", V, F, N, tessellation="thesis")
    assert m.name == "quadric-implicit-robust"
    assert m.representation == "implicit"
    assert m.patch_count == 20
    assert m.tessellation == "thesis"
    assert "quadric-implicit-robust" in repr(m)
    assert quadtri.Model("shading", V, F, N).representation == "input-triangles"
    assert quadtri.Model("nagata", V, F, N).representation == "tessellated"


@pytest.mark.parametrize("model", ["quadric-param", "quadric-edges-eq42", "shading"])
def test_tessellate_matches_convert(cli, tmp_path, model):
    out = tmp_path / "t.obj"
    cli("convert", "icosahedron", "--model", model, "--tessellation", 3, "-o", out)
    # eq42 is not welded: its patches' edge points differ, and the loader welds positions.
    V, F, N, NI = quadtri.load_mesh(out, split=True)
    m = quadtri.Model(model, *quadtri.shape("icosahedron"))
    TV, TF, TN = m.tessellate(3)
    assert TF.shape == (20 * (9 if model != "shading" else 1), 3)
    # The same triangles in the same order; the loader reads the OBJ's 17 digits as floats.
    np.testing.assert_allclose(TV[TF], V[F], rtol=0, atol=1e-7)
    np.testing.assert_allclose(TN[TF], N[NI], rtol=0, atol=1e-7)


@pytest.mark.parametrize("model", ["pn", "quadric-g1", "quadric-edges-eq42", "shading"])
def test_save_writes_what_convert_writes(cli, tmp_path, model):
    cli("convert", "torus", "--model", model, "--tessellation", 2, "-o", tmp_path / "cli.obj")
    m = quadtri.Model(model, *quadtri.shape("torus"))
    written = m.save(tmp_path / "py.obj", level=2)
    assert (tmp_path / "py.obj").read_bytes() == (tmp_path / "cli.obj").read_bytes()
    TV, TF, TN = m.tessellate(2)
    assert written == len(TF)
    # PLY, streamed: its vertices are the tessellation's points, in order (as floats).
    assert m.save(tmp_path / "py.ply", level=2) == len(TF)
    # eq42 does not weld: the loader welds its patches' equal corners, keeping their normals.
    V, F, N, NI = quadtri.load_mesh(tmp_path / "py.ply", split=True)
    np.testing.assert_allclose(TV[TF], V[F], rtol=0, atol=1e-6)
    np.testing.assert_allclose(TN[TF], N[NI], rtol=0, atol=1e-6)
    # Patches name the tessellation convert names (an automatic one, the level it resolves to).
    cli("convert", "torus", "--model", model, "--tessellation", "auto", "-o", tmp_path / "cli.json")
    assert m.save(tmp_path / "py.json", level="auto") == 0
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    with pytest.raises(quadtri.Error, match=r"x\.stl"):
        m.save(tmp_path / "x.stl")
    assert not (tmp_path / "x.stl").exists()


@pytest.mark.parametrize("subdivisions, level", [(0, 8), (4, 2), (6, 1)])
def test_auto_tessellation_picks_the_level_convert_picks(cli, tmp_path, subdivisions, level):
    out = tmp_path / "t.ply"
    spec = f"icosphere:{subdivisions}"
    printed = cli("convert", spec, "--model", "pn", "--tessellation", "auto", "-o", out).stdout
    assert f"tessellation {level} (auto)" in printed
    shape = quadtri.shape("icosphere", level=subdivisions)
    m = quadtri.Model("pn", *shape, tessellation="auto")
    assert m.tessellation == level
    V, F, N = quadtri.load_mesh(out)
    TV, TF, TN = m.tessellate()
    assert TF.shape == F.shape
    np.testing.assert_allclose(TV[TF], V[F], rtol=0, atol=1e-7)
    assert quadtri.Model("pn", *shape, tessellation="auto:0.9").tessellation == 1
    # A model traced as it is picks its level only when it is tessellated.
    implicit = quadtri.Model("quadric-implicit", *shape, tessellation="auto")
    assert implicit.tessellation == "auto"
    assert "tessellation='auto'" in repr(implicit)


def test_evaluate_reproduces_corners_and_broadcasts():
    V, F, N = quadtri.shape("icosphere", level=1)
    m = quadtri.Model("quadric-implicit-robust", V, F, N)
    t = np.arange(m.patch_count)
    for k, (u, v) in enumerate([(0, 0), (1, 0), (0, 1)]):
        P, Nrm = m.evaluate(t, u, v)
        assert P.shape == (80, 3)
        np.testing.assert_allclose(P, V[F[:, k]], atol=1e-12)
        np.testing.assert_allclose(Nrm, N[F[:, k]], atol=1e-9)
    P, Nrm = m.evaluate(3, np.linspace(0, 0.5, 4)[:, None], np.linspace(0, 0.5, 5)[None, :])
    assert P.shape == (4, 5, 3)
    np.testing.assert_allclose(np.linalg.norm(P, axis=-1), 1.0, atol=1e-9)  # the unit sphere
    np.testing.assert_allclose(Nrm, P, atol=1e-9)
    # Points off the patch (NaN included) are refused, naming the first one.
    for u, v, where in ((np.nan, 0.3, "(nan, 0.3) at index 0"), (2.0, 2.0, "(2, 2) at index 0"),
                        ([0.2, -0.1], 0.1, "(-0.1, 0.1) at index 1")):
        with pytest.raises(ValueError, match=re.escape(where)):
            m.evaluate(0, u, v)
    P, _ = m.evaluate(0, 0.5 + 1e-12, 0.5)  # rounding on the edge u + v = 1 is a point of it
    assert np.isfinite(P).all()


def to_array(value):
    return np.asarray(value, dtype=float)


def check_records(records, entries):
    """Every key of every JSON entry is a field of its record with the same numbers."""
    assert len(records) == len(entries)
    for record, entry in zip(records, entries):
        for key, value in entry.items():
            if isinstance(value, str):
                continue
            if isinstance(value, dict):
                check_records(np.array([record[key]]), [value])
                continue
            got = record[key]
            if key == "planes":
                n = record["planes_count"]
                assert n == len(value)
                np.testing.assert_array_equal(got[:n], to_array(value).reshape(n, 4))
                assert not got[n:].any()
            else:
                np.testing.assert_array_equal(np.asarray(got, dtype=float), to_array(value))


@pytest.mark.parametrize("model", quadtri.model_names())
def test_patches_match_convert_json(cli, tmp_path, model):
    out = tmp_path / "p.json"
    cli("convert", "torus:1,0.35,12,6", "--model", model, "-o", out)
    want = json.loads(out.read_text())
    m = quadtri.Model(model, *quadtri.load_mesh("torus:1,0.35,12,6"))
    assert m.patch_json() == want
    patches = m.patches()
    assert patches.shape == (m.patch_count,)
    check_records(patches, want["patches"])
    bridges = m.bridges()
    check_records(bridges, want.get("bridges", []))
    assert {"bounds", "joins", "plane"} <= set(bridges.dtype.names)


def test_implicit_patch_records():
    V, F, N = quadtri.shape("icosphere", level=1)
    p = quadtri.Model("quadric-implicit-robust", V, F, N).patches()
    assert p["quadric"].shape == (80, 10) and p["planes"].shape == (80, 6, 4)
    assert p["bounds"]["min"].shape == (80, 3) and p["flat"].dtype == bool
    # Each patch is the unit sphere x² + y² + z² − 1 = 0 (up to scale).
    q = p["quadric"] / p["quadric"][:, :1]
    np.testing.assert_allclose(q, np.tile([1, 1, 1, 0, 0, 0, 0, 0, 0, -1], (80, 1)), atol=1e-9)
    # Every corner is inside its patch's planes and bounds.
    corners = V[F]  # (80, 3, 3)
    side = np.einsum("tpk,tck->tcp", p["planes"][:, :, :3], corners) + p["planes"][:, None, :, 3]
    assert (side > -1e-9).all()
    assert (corners >= p["bounds"]["min"][:, None] - 1e-12).all()
    assert (corners <= p["bounds"]["max"][:, None] + 1e-12).all()
    assert len(quadtri.Model("quadric-implicit-robust", V, F, N).bridges()) == 0


def test_bridges_on_a_torus():
    m = quadtri.Model("quadric-implicit-robust", *quadtri.shape("torus", segments=16, rings=8))
    b = m.bridges()
    assert len(b) > 0
    assert ((b["joins"] >= 0) & (b["joins"] < m.patch_count)).all()
    # A bridge is clipped by the planes of the two cells it joins (join_planes), not by planes of
    # its own.
    assert b["join_planes"].shape == (len(b), 2)
    np.testing.assert_allclose(np.linalg.norm(b["plane"][:, :3], axis=1), 1.0, atol=1e-9)


def same_records(a, b):
    """Equal structured arrays: one dtype, the same bytes (NaN where one is NaN)."""
    assert a.dtype == b.dtype
    assert a.shape == b.shape
    assert a.tobytes() == b.tobytes()


@pytest.mark.parametrize("model", quadtri.model_names())
def test_read_patches_matches_patches(cli, tmp_path, model):
    out = tmp_path / "p.qtp"
    cli("convert", "torus:1,0.35,12,6", "--model", model, "-o", out)
    table = quadtri.read_patches(out)
    m = quadtri.Model(model, *quadtri.load_mesh("torus:1,0.35,12,6"))
    assert table["model"] == model
    assert table["tessellation"] == "8"
    assert table["triangles"] == m.patch_count
    same_records(table["patches"], m.patches())
    same_records(table["bridges"], m.bridges())
    # And the JSON the CLI writes beside it holds the same values.
    json_out = tmp_path / "p.json"
    cli("convert", "torus:1,0.35,12,6", "--model", model, "-o", json_out)
    check_records(table["patches"], json.loads(json_out.read_text())["patches"])


def test_read_patches_rejects_a_bad_file_naming_it_and_the_offset(cli, tmp_path):
    out = tmp_path / "p.qtp"
    cli("convert", "icosahedron", "--model", "quadric-implicit", "-o", out)
    data = out.read_bytes()
    bad = tmp_path / "bad.qtp"
    bad.write_bytes(b"NOTAQTP\0" + data[8:])
    with pytest.raises(quadtri.Error, match=r"bad\.qtp: offset 0: not a quadtri patch table"):
        quadtri.read_patches(bad)
    bad.write_bytes(data[:-5])
    with pytest.raises(quadtri.Error, match=r"bad\.qtp: offset \d+: the header declares 20 patches"):
        quadtri.read_patches(bad)
