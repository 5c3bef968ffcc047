"""Meshes in and out: built-in shapes, files, split normals, round trips of the arrays."""

import numpy as np
import pytest

import quadtri


def test_module_is_a_package_with_the_extension():
    assert quadtri.__version__
    assert quadtri.Model.__module__.startswith("quadtri")
    assert issubclass(quadtri.Error, RuntimeError)
    assert issubclass(quadtri.SplitNormalsWarning, UserWarning)
    assert "quadric-implicit-robust" in quadtri.model_names()
    assert quadtri.model_names()[0] == "flat"
    assert "icosphere" in quadtri.shape_names()


def test_shape_gives_libigl_arrays():
    V, F, N = quadtri.shape("icosphere", level=1)
    assert V.dtype == np.float64 and V.shape == (42, 3)
    assert F.dtype == np.int64 and F.shape == (80, 3)
    assert N.dtype == np.float64 and N.shape == (42, 3)
    assert V.flags.c_contiguous and F.flags.c_contiguous
    assert F.min() == 0 and F.max() == 41
    np.testing.assert_allclose(np.linalg.norm(V, axis=1), 1.0, atol=1e-15)
    np.testing.assert_allclose(N, V, atol=1e-15)  # the sphere's analytic normals


def test_shape_truth_and_parameters():
    V, F, N, S = quadtri.shape("torus", major=1.0, minor=0.25, segments=12, rings=6, truth=True)
    assert F.shape == (2 * 12 * 6, 3)
    assert S.kind == "torus" and S.a == 1.0 and S.b == 0.25
    np.testing.assert_allclose(S.distance(V), 0.0, atol=1e-12)
    np.testing.assert_allclose(S.normal(V), N, atol=1e-12)
    assert S.size == pytest.approx(1.25)
    _, _, Navg = quadtri.shape("torus", major=1.0, minor=0.25, segments=12, rings=6,
                               normals="average")
    assert not np.allclose(Navg, N, atol=1e-6)
    np.testing.assert_allclose(np.linalg.norm(Navg, axis=1), 1.0, atol=1e-12)


def test_load_mesh_takes_files_and_specs_like_the_cli(repo):
    V, F, N = quadtri.load_mesh("icosphere:1")
    V2, F2, N2 = quadtri.shape("icosphere", level=1)
    np.testing.assert_array_equal(V, V2)
    np.testing.assert_array_equal(F, F2)
    np.testing.assert_array_equal(N, N2)
    V, F, N, S = quadtri.load_mesh(repo / "scenes/meshes/icosahedron.obj", truth=True)
    assert V.shape == (12, 3) and F.shape == (20, 3) and S is None
    _, _, _, S = quadtri.load_mesh("ellipsoid:1,0.7,0.5", truth=True)
    assert (S.kind, S.a, S.b, S.c) == ("ellipsoid", 1.0, 0.7, 0.5)


@pytest.mark.parametrize("ext", ["obj", "ply"])
def test_save_and_load_round_trip(tmp_path, ext):
    V, F, N = quadtri.shape("ellipsoid", level=1)
    path = tmp_path / f"e.{ext}"
    quadtri.save_mesh(path, V, F, N)
    V2, F2, N2 = quadtri.load_mesh(path)
    # The same triangles in the same order, their vertices possibly renumbered; the loader reads
    # coordinates as floats (Assimp), so to float precision.
    assert F2.shape == F.shape and len(V2) == len(V)
    np.testing.assert_allclose(V2[F2], V[F], rtol=0, atol=1e-7)
    np.testing.assert_allclose(N2[F2], N[F], rtol=0, atol=1e-7)


def test_model_keeps_its_input_arrays():
    V, F, N = quadtri.shape("torus", segments=10, rings=5)
    m = quadtri.Model("quadric-param", V, F, N)
    V2, F2, N2 = m.mesh()
    np.testing.assert_array_equal(V2, V)
    np.testing.assert_array_equal(F2, F)
    np.testing.assert_array_equal(N2, N)
    # Lists, other float and integer dtypes and non-contiguous views are converted.
    m2 = quadtri.Model("quadric-param", V.astype(np.float32).tolist(), F.astype(np.uint32),
                       np.asfortranarray(N))
    np.testing.assert_array_equal(m2.mesh()[0], V.astype(np.float32).astype(np.float64))
    assert m2.mesh()[1].dtype == np.int64


CUBE = """\
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
f 1//1 3//1 2//1
f 1//1 4//1 3//1
f 5//2 6//2 7//2
f 5//2 7//2 8//2
f 1//3 2//3 6//3
f 1//3 6//3 5//3
f 4//4 8//4 7//4
f 4//4 7//4 3//4
f 1//5 5//5 8//5
f 1//5 8//5 4//5
f 2//6 3//6 7//6
f 2//6 7//6 6//6
"""


def test_split_normals(tmp_path):
    path = tmp_path / "cube.obj"
    path.write_text(CUBE)
    with pytest.warns(quadtri.SplitNormalsWarning, match="8 of 8 vertices have split normals"):
        V, F, N = quadtri.load_mesh(path)
    # Each corner of the cube gets the mean of its three face normals (not weighted by how many
    # triangles of each face meet there).
    np.testing.assert_allclose(N, V / np.sqrt(3), atol=1e-15)
    V, F, N, NI = quadtri.load_mesh(path, split=True)
    assert N.shape == (6, 3) and NI.shape == (12, 3)
    corner_normals = N[NI]  # (m, 3, 3): the normal of corner j of triangle i
    face = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    face /= np.linalg.norm(face, axis=1, keepdims=True)
    np.testing.assert_allclose(corner_normals, np.repeat(face[:, None], 3, axis=1), atol=1e-15)
    m = quadtri.Model("shading", V, F, N, NI)
    V2, F2, N2, NI2 = m.mesh(split=True)
    np.testing.assert_array_equal(N2[NI2], corner_normals)
    # Split normals survive the model: its tessellation is its input.
    _, _, N3, NI3 = m.tessellate(split=True)
    np.testing.assert_array_equal(N3[NI3], corner_normals)


def test_without_normals_the_model_computes_eq_2_8():
    V, F, _ = quadtri.shape("icosphere", level=1)
    _, _, Navg = quadtri.shape("icosphere", level=1, normals="average")
    m = quadtri.Model("shading", V, F)
    np.testing.assert_allclose(m.mesh()[2], Navg, atol=1e-15)


def test_surface_kinds():
    s = quadtri.Surface("sphere", 2.0)
    P = np.array([[3.0, 0, 0], [0, 0, 1.0]])
    np.testing.assert_allclose(s.distance(P), [1.0, 1.0])
    np.testing.assert_allclose(s.normal(P), [[1, 0, 0], [0, 0, 1]])
    assert "sphere" in repr(s)
    with pytest.raises(ValueError, match="kind 'cube'"):
        quadtri.Surface("cube")


def test_load_mesh_reports_repairs_naming_the_file(tmp_path):
    # Two squares' worth of triangles, one duplicated and one naming a vertex twice.
    path = tmp_path / "damaged.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                    "f 1 2 3\nf 1 3 4\nf 3 2 1\nf 1 1 2\n")
    with pytest.warns(UserWarning, match=r"damaged\.obj: removed 1 triangle naming a vertex "
                                         r"twice and 1 duplicate triangle"):
        V, F, N = quadtri.load_mesh(path)
    assert F.shape == (2, 3)
