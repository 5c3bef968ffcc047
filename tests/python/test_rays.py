"""RayScene.cast_rays against analytic answers and an independent triangle intersection."""

import threading

import numpy as np
import pytest

import quadtri


def random_rays(rng, k, radius=3.0, aim=0.9):
    """Rays from a sphere of `radius` towards random points of the ball of radius `aim`."""
    o = rng.normal(size=(k, 3))
    o *= radius / np.linalg.norm(o, axis=1, keepdims=True)
    target = rng.normal(size=(k, 3))
    target *= aim * rng.random((k, 1)) ** (1 / 3) / np.linalg.norm(target, axis=1, keepdims=True)
    d = target - o
    return o, d / np.linalg.norm(d, axis=1, keepdims=True)


def sphere_t(o, d):
    """Nearest root of |o + t d| = 1 for unit d."""
    b = np.einsum("ij,ij->i", o, d)
    c = np.einsum("ij,ij->i", o, o) - 1.0
    return -b - np.sqrt(b * b - c)


def test_robust_icosphere_reproduces_the_unit_sphere():
    V, F, N = quadtri.shape("icosphere", level=2)
    m = quadtri.Model("quadric-implicit-robust", V, F, N)
    scene = quadtri.RayScene([m])
    o, d = random_rays(np.random.default_rng(1), 20000)
    hit = scene.cast_rays(o, d)
    assert set(hit) == {"t", "position", "geometric_normal", "shading_normal", "primitive",
                        "patch", "geometry"}
    assert (hit["geometry"] == 0).all()
    np.testing.assert_allclose(hit["t"], sphere_t(o, d), rtol=0, atol=1e-9)
    p = hit["position"]
    np.testing.assert_allclose(np.linalg.norm(p, axis=1), 1.0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(p, o + hit["t"][:, None] * d, rtol=0, atol=1e-9)
    np.testing.assert_allclose(hit["geometric_normal"], p, rtol=0, atol=1e-9)
    np.testing.assert_allclose(hit["shading_normal"], p, rtol=0, atol=1e-9)
    # No bridges on a sphere: the primitive is the patch, and the patch's triangle lies under
    # the hit (the ray through the hit from the centre crosses that triangle).
    assert ((hit["primitive"] >= 0) & (hit["primitive"] < m.patch_count)).all()
    np.testing.assert_array_equal(hit["patch"], hit["primitive"])
    a, b, c = (V[F[hit["patch"], k]] for k in range(3))
    normals = np.cross(b - a, c - a)
    for e0, e1 in ((a, b), (b, c), (c, a)):
        assert (np.einsum("ij,ij->i", np.cross(e0, e1), p) >= -1e-9).all()
    assert (np.einsum("ij,ij->i", normals, p) > 0).all()


def test_the_consumers_ray():
    """examples/consumer's ray (scripts/check-install.sh): straight down through (0.1, 0.05)."""
    m = quadtri.Model("quadric-implicit-robust", *quadtri.load_mesh("icosphere:1"))
    hit = quadtri.RayScene([m]).cast_rays([0.1, 0.05, 3.0], [0.0, 0.0, -1.0])
    z = np.sqrt(1 - 0.1**2 - 0.05**2)
    assert hit["t"][0] == pytest.approx(3.0 - z, abs=1e-12)
    np.testing.assert_allclose(hit["geometric_normal"][0], [0.1, 0.05, z], atol=1e-12)


def moller_trumbore(o, d, V, F):
    """Nearest hit of each ray with the triangles, in numpy (an independent reference)."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    e1, e2 = b - a, c - a
    t_best = np.full(len(o), np.inf)
    prim = np.full(len(o), -1)
    bary = np.zeros((len(o), 2))
    for i in range(len(o)):
        pv = np.cross(d[i], e2)
        det = np.einsum("ij,ij->i", e1, pv)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            tv = o[i] - a
            u = np.einsum("ij,ij->i", tv, pv) * inv
            qv = np.cross(tv, e1)
            v = (qv @ d[i]) * inv
            t = np.einsum("ij,ij->i", e2, qv) * inv
        ok = (np.abs(det) > 1e-14) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        if ok.any():
            j = np.flatnonzero(ok)[np.argmin(t[ok])]
            t_best[i], prim[i], bary[i] = t[j], j, (u[j], v[j])
    return t_best, prim, bary


@pytest.mark.parametrize("model", ["quadric-param", "shading", "flat"])
def test_triangle_models_match_an_independent_intersection(model):
    V, F, N = quadtri.shape("torus", segments=12, rings=6)
    m = quadtri.Model(model, V, F, N, tessellation=3)
    TV, TF, TN = m.tessellate()
    o, d = random_rays(np.random.default_rng(2), 400, radius=3.0, aim=1.3)
    hit = quadtri.RayScene([m]).cast_rays(o, d)
    t, prim, bary = moller_trumbore(o, d, TV, TF)
    # Rays whose nearest hits are within float noise of an edge may pick either triangle.
    clear = (bary.min(axis=1) > 1e-4) & (bary.sum(axis=1) < 1 - 1e-4) | (prim < 0)
    assert clear.mean() > 0.9
    np.testing.assert_array_equal(hit["primitive"][clear], prim[clear])
    hits = clear & (prim >= 0)
    assert hits.sum() > 100
    np.testing.assert_allclose(hit["t"][hits], t[hits], rtol=0, atol=1e-5)  # Embree's floats
    # The renderer puts the point on the triangle from its double barycentrics.
    np.testing.assert_allclose(hit["position"][hits], (o + t[:, None] * d)[hits], atol=1e-5)
    per_patch = 9 if model == "quadric-param" else 1
    np.testing.assert_array_equal(hit["patch"][hits], prim[hits] // per_patch)
    tri = TF[prim[hits]]
    face = np.cross(TV[tri[:, 1]] - TV[tri[:, 0]], TV[tri[:, 2]] - TV[tri[:, 0]])
    face /= np.linalg.norm(face, axis=1, keepdims=True)
    np.testing.assert_allclose(hit["geometric_normal"][hits], face, atol=1e-12)
    if model == "flat":
        np.testing.assert_allclose(hit["shading_normal"][hits], face, atol=1e-12)
    else:
        # Interpolated normals at Embree's barycentrics (floats): close to the exact ones.
        u, v = bary[hits, 0:1], bary[hits, 1:2]
        n = (1 - u - v) * TN[tri[:, 0]] + u * TN[tri[:, 1]] + v * TN[tri[:, 2]]
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        np.testing.assert_allclose(hit["shading_normal"][hits], n, atol=1e-5)
    assert (hit["t"][prim < 0] == np.inf).all()


def test_misses_and_ray_intervals():
    m = quadtri.Model("quadric-implicit-robust", *quadtri.shape("icosphere", level=1))
    scene = quadtri.RayScene([m])
    o = np.array([[0, 0, 3.0], [0, 0, 3.0], [0, 0, 3.0], [5, 5, 5.0]])
    d = np.array([[0, 0, -1.0], [0, 0, 1.0], [0, 0, -2.0], [0, 0, -1.0]])
    hit = scene.cast_rays(o, d)
    assert hit["t"][0] == pytest.approx(2.0, abs=1e-12)
    assert hit["t"][2] == pytest.approx(1.0, abs=1e-12)  # t in units of |d|
    for i in (1, 3):
        assert hit["t"][i] == np.inf
        assert hit["primitive"][i] == hit["patch"][i] == hit["geometry"][i] == -1
        assert np.isnan(hit["position"][i]).all()
        assert (hit["geometric_normal"][i] == 0).all() and (hit["shading_normal"][i] == 0).all()
    far = scene.cast_rays(o[:1], d[:1], tnear=2.5)  # past the front: the back of the sphere
    assert far["t"][0] == pytest.approx(4.0, abs=1e-12)
    assert scene.cast_rays(o[:1], d[:1], tfar=1.5)["t"][0] == np.inf
    np.testing.assert_array_equal(scene.occluded(o, d), [True, False, True, False])
    np.testing.assert_array_equal(scene.occluded(o, d, tfar=1.5), [False, False, True, False])
    empty = scene.cast_rays(np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty["t"].shape == (0,) and empty["position"].shape == (0, 3)


def test_several_models_and_broadcasting():
    V, F, N = quadtri.shape("icosphere", level=1)
    a = quadtri.Model("quadric-implicit-robust", V, F, N)
    b = quadtri.Model("shading", V + [3.0, 0, 0], F, N)
    scene = quadtri.RayScene([a, b])
    assert len(scene) == 2
    assert scene.primitive_count == 160 and scene.geometry_bytes > 0
    # One origin, many directions (and the other way round).
    hit = scene.cast_rays([0.0, 0.0, 5.0], [[0, 0, -1.0], [0.6, 0, -1.0], [0, 0, 1.0]])
    np.testing.assert_array_equal(hit["geometry"], [0, 1, -1])
    hit = scene.cast_rays([[0, 0, 5.0], [3, 0, 5.0]], [0, 0, -1.0])
    np.testing.assert_array_equal(hit["geometry"], [0, 1])
    assert hit["t"][1] == pytest.approx(4.0, abs=1e-6)  # the icosphere's vertex at the pole


def test_float_mode_and_threads():
    """Tracing leaves the caller's denormals alone and runs from several Python threads."""
    m = quadtri.Model("quadric-implicit-robust", *quadtri.shape("icosphere", level=2))
    scene = quadtri.RayScene([m])
    o, d = random_rays(np.random.default_rng(3), 5000)
    want = scene.cast_rays(o, d)["t"]
    m.analyze(lines=2000)
    tiny = np.array([1e-310])
    assert (tiny * 0.5)[0] != 0.0, "flush-to-zero leaked into the caller's thread"
    results = [None] * 4

    def work(i):
        results[i] = scene.cast_rays(o, d)["t"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        np.testing.assert_array_equal(r, want)


def test_hits_do_not_depend_on_the_thread_count():
    """Rays aimed at the vertices of a triangle mesh hit several triangles at one t, and Embree's
    packet kernel may settle such a tie by the other rays of the packet: which triangle wins must
    not depend on how the rays were shared between threads (nor must any other hit). Each ray
    comes five times in a row, so that its copies sit at different places in their packets."""
    V, F, N = quadtri.shape("icosphere", level=3)
    rng = np.random.default_rng(7)
    origins = np.repeat(3.0 * V[rng.integers(0, len(V), 4000)], 5, axis=0)
    targets = np.repeat(V[rng.integers(0, len(V), 4000)], 5, axis=0)
    scene = quadtri.RayScene([quadtri.Model("shading", V, F, N),
                              quadtri.Model("quadric-implicit", V + [3.0, 0, 0], F, N)])
    o = np.concatenate([origins, origins + [3.0, 0, 0]])
    d = np.concatenate([targets, targets + [3.0, 0, 0]]) - o
    one = scene.cast_rays(o, d, threads=1)
    assert (one["geometry"] >= 0).mean() > 0.9
    for threads in (2, 3, 0):
        other = scene.cast_rays(o, d, threads=threads)
        for key in one:
            np.testing.assert_array_equal(other[key], one[key], err_msg=f"{key}, {threads} threads")
    np.testing.assert_array_equal(scene.occluded(o, d, threads=1), scene.occluded(o, d, threads=2))
    with pytest.raises(ValueError, match="threads = -1"):
        scene.cast_rays(o, d, threads=-1)
