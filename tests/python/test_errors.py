"""Errors: the library's messages as quadtri.Error (the CLI's text), and arguments of the wrong
shape or dtype rejected with a message naming them."""

import pathlib

import numpy as np
import pytest

import quadtri
from conftest import cli_error


def message(fn, *args, **kwargs):
    with pytest.raises(quadtri.Error) as e:
        fn(*args, **kwargs)
    return str(e.value)


def test_error_is_a_runtime_error():
    assert issubclass(quadtri.Error, RuntimeError)
    with pytest.raises(RuntimeError):
        quadtri.load_mesh("no-such-mesh.obj")


def test_mesh_errors_carry_the_clis_message(cli, tmp_path):
    assert message(quadtri.load_mesh, "no-such-mesh.obj") == cli_error(
        cli("analyze", "no-such-mesh.obj", check=False))
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    assert message(quadtri.load_mesh, bad) == cli_error(cli("analyze", bad, check=False))
    assert "bad.obj" in message(quadtri.load_mesh, bad)
    assert message(quadtri.load_mesh, "icosphere:x") == cli_error(
        cli("analyze", "icosphere:x", check=False))


def test_model_errors_carry_the_clis_message(cli):
    V, F, N = quadtri.shape("icosahedron")
    assert message(quadtri.Model, "no-such-model", V, F, N) == cli_error(
        cli("analyze", "icosahedron", "--model", "no-such-model", check=False))
    assert message(quadtri.Model, "pn", V, F, N, tessellation=300) == cli_error(
        cli("analyze", "icosahedron", "--tessellation", 300, check=False))
    assert message(quadtri.shape, "icosphere", level=-1) == cli_error(
        cli("mesh", "icosphere", "--level", -1, "-o", "never.obj", check=False))


def test_render_errors_carry_the_clis_message(cli, tmp_path):
    scene = tmp_path / "bad.xml"
    scene.write_text('<scene version="3.0.0">\n  <shape type="teapot"/>\n</scene>\n')
    want = cli_error(cli("render", scene, "-o", tmp_path / "x.exr", check=False))
    assert message(quadtri.render, scene) == want
    assert want.startswith(f"{scene}:2: ")
    assert "no-such.xml" in message(quadtri.render, tmp_path / "no-such.xml")
    assert "spp 0" in message(quadtri.render, scene, spp=0)


V, F, N = quadtri.shape("icosahedron")


@pytest.mark.parametrize(
    "args, kind, words",
    [
        ((V[:, :2], F, N), ValueError, ["V", "(n, 3)", "(12, 2)"]),
        ((V.astype(complex), F, N), TypeError, ["V", "float", "complex128"]),
        ((V > 0, F, N), TypeError, ["V", "float", "bool"]),
        ((V[0], F, N), ValueError, ["V", "(n, 3)", "(3,)"]),
        (("not an array", F, N), TypeError, ["V", "float"]),
        ((V, F.astype(float), N), TypeError, ["F", "integer", "float64"]),
        ((V, F[:, :2], N), ValueError, ["F", "(m, 3)", "(20, 2)"]),
        ((V, F.astype(bool), N), TypeError, ["F", "integer", "bool"]),
        ((V, np.where(F == 5, 12, F), N), ValueError, ["F[", "= 12", "[0, 12)"]),
        ((V, np.where(F == 5, -1, F), N), ValueError, ["F[", "= -1"]),
        ((V, F, N[:5]), ValueError, ["N", "(12, 3)", "(5, 3)", "NI"]),
        ((V, F, 2 * N), ValueError, ["N[0]", "unit"]),
        ((V, F, N, F[:3]), ValueError, ["NI", "(20, 3)"]),
        ((V, F, N, F.astype(np.float32)), TypeError, ["NI", "integer"]),
    ],
)
def test_model_rejects_bad_arrays(args, kind, words):
    with pytest.raises(kind) as e:
        quadtri.Model("pn", *args)
    for w in words:
        assert w in str(e.value), (w, str(e.value))


def test_cast_rays_rejects_bad_arrays():
    scene = quadtri.RayScene([quadtri.Model("flat", V, F, N)])
    o = np.zeros((4, 3))
    d = np.tile([0, 0, 1.0], (4, 1))
    with pytest.raises(ValueError, match=r"origins: expected a float array of shape \(k, 3\) or "
                                         r"\(3,\), got shape \(4, 2\)"):
        scene.cast_rays(o[:, :2], d)
    with pytest.raises(TypeError, match=r"directions: expected a float array of shape .* got dtype bool"):
        scene.cast_rays(o, d > 0)
    with pytest.raises(ValueError, match=r"4 origins and 3 directions"):
        scene.cast_rays(o, d[:3])
    with pytest.raises(ValueError, match=r"origins: row 2 is not finite"):
        scene.cast_rays(np.where(np.arange(12).reshape(4, 3) == 7, np.nan, o), d)
    # Finite but beyond what Embree traces (its assertion aborted the interpreter).
    with pytest.raises(ValueError, match=r"origins: row 0 has a coordinate of 1e\+30: expected one "
                                         r"within ±1.84e\+18"):
        scene.cast_rays([1e30, 0, 0], [0, 0, 1.0])
    with pytest.raises(ValueError, match=r"directions: row 3 has a coordinate"):
        scene.cast_rays(o, np.where(np.arange(12).reshape(4, 3) == 11, -2e18, d))
    with pytest.raises(ValueError, match=r"tnear"):
        scene.cast_rays(o, d, tnear=2.0, tfar=1.0)
    with pytest.raises(TypeError):
        quadtri.RayScene([V])


def test_other_argument_errors():
    m = quadtri.Model("quadric-param", V, F, N)
    with pytest.raises(ValueError, match=r"t: patch 20 out of range \[0, 20\)"):
        m.evaluate(20, 0.1, 0.1)
    with pytest.raises(TypeError, match=r"u: expected a float array, got dtype"):
        m.evaluate(0, "x", 0.1)
    with pytest.raises(ValueError, match="lines 0"):
        m.analyze(lines=0)
    with pytest.raises(TypeError, match="tessellation"):
        m.tessellate(2.5)
    with pytest.raises(ValueError, match="normals 'bent'"):
        quadtri.shape("torus", normals="bent")
    with pytest.raises(quadtri.Error, match="bent"):
        quadtri.load_mesh("torus", normals="bent")
    with pytest.raises(TypeError, match=r"defines\['res'\]"):
        quadtri.render("scene.xml", defines={"res": [1]})
    with pytest.raises(ValueError, match="P: expected a float array of shape \\(k, 3\\)"):
        quadtri.Surface("sphere").distance(np.zeros(3))
    # Counts and seeds: a negative or fractional one is named (pybind11 alone would only say
    # the arguments are incompatible); numpy integers are whole numbers too.
    with pytest.raises(ValueError, match=r"lines = -1: expected a whole number"):
        m.analyze(lines=-1)
    with pytest.raises(ValueError, match=r"seed = -1: expected a whole number"):
        m.analyze(lines=10, seed=-1)
    with pytest.raises(TypeError, match="lines: expected an int, got a float"):
        m.analyze(lines=2.5)
    with pytest.raises(ValueError, match=r"seed = -1: expected a whole number"):
        quadtri.render("scene.xml", seed=-1)
    assert m.analyze(lines=np.int64(10), seed=np.uint64(2**64 - 1))["crack_rate"] is not None
    with pytest.raises(TypeError, match="expected an integer array"):
        quadtri.Model("flat", V, F.astype(float))
    with pytest.raises(ValueError, match=r"F: shape \(0, 3\): a model is built from at least one"):
        quadtri.Model("pn", np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
    with pytest.raises(quadtri.Error, match="a folder, expected a scene file"):
        quadtri.render(pathlib.Path(__file__).parent)
    with pytest.raises(ValueError, match=r"F: row 1 \(0, 2, 0\) names a vertex twice"):
        quadtri.Model("flat", V, np.array([[0, 1, 2], [0, 2, 0]]))
    with pytest.raises(TypeError, match="lines: expected an int, got a bool"):
        m.analyze(lines=np.True_)
