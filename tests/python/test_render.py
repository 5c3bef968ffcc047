"""render(): the CLI's images, a white furnace, warnings and statistics."""

import re

import numpy as np
import pytest

import quadtri

try:
    import OpenImageIO as oiio
except ImportError:  # Debian's python3-openimageio
    oiio = None

FURNACE = "tests/python/scenes/furnace.xml"
THESIS = "scenes/thesis/a-icosahedron.xml"


def read_exr(path):
    image = oiio.ImageInput.open(str(path))
    assert image, oiio.geterror()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return pixels


def test_white_furnace(repo):
    """A white diffuse sphere (the robust model's icosahedron) under a constant environment of
    radiance 1: every pixel's expected value is 1."""
    img = quadtri.render(repo / FURNACE, spp=64, defines={"res": 8})
    assert img.dtype == np.float32 and img.shape == (8, 8, 3) and img.flags.c_contiguous
    assert np.isfinite(img).all()
    np.testing.assert_array_equal(img[..., 0], img[..., 2])  # grey in, grey out
    pixels = img[..., 0].ravel()
    sigma = pixels.std(ddof=1) / np.sqrt(pixels.size)
    assert 0 < sigma < 0.01
    assert abs(pixels.mean() - 1.0) < 4 * sigma, (pixels.mean(), sigma)


@pytest.mark.skipif(oiio is None, reason="needs Debian's python3-openimageio")
@pytest.mark.parametrize("model", ["quadric-implicit-robust", "shading"])
def test_same_image_as_the_cli(cli, repo, tmp_path, model):
    exr = tmp_path / "cli.exr"
    out = cli("render", repo / THESIS, "-D", "res=24", "--spp", 3, "--seed", 9, "--model", model,
              "--threads", 1, "-o", exr).stdout
    want = read_exr(exr)
    img, stats = quadtri.render(repo / THESIS, spp=3, seed=9, model=model, defines={"res": 24},
                                return_stats=True)
    assert img.shape == want.shape == (24, 24, 3)
    np.testing.assert_array_equal(img, want)  # bit for bit: same code, same seeds
    assert img.mean() == want.mean()
    assert img.mean() > 0.01
    prims = re.search(r"primitives\s+(\d+) \(from (\d+) input triangles\)", out)
    assert (stats["primitives"], stats["input_triangles"]) == tuple(map(int, prims.groups()))
    assert stats["integrator"] in out
    assert stats["samples_per_pixel"] == 3.0
    assert (stats["width"], stats["height"]) == (24, 24)
    assert stats["rays"] > 0 and stats["unfinished_pixels"] == 0
    assert 0 < stats["first_pixel_seconds"] <= stats["seconds"]
    # The CLI's first pixel counts from the opening of the scene file: after the build.
    build = float(re.search(r"scene build\s+([0-9.]+) s", out).group(1))
    first = float(re.search(r"first pixel\s+([0-9.]+) s", out).group(1))
    assert 0 <= build <= first
    assert float(re.search(r"peak memory\s+([0-9.]+) MiB", out).group(1)) > 1.0


def test_defines_take_numbers_and_bools(repo):
    a = quadtri.render(repo / FURNACE, defines={"res": 4, "spp": 2})
    b = quadtri.render(repo / FURNACE, defines={"res": "4", "spp": "2"})
    np.testing.assert_array_equal(a, b)
    assert a.shape == (4, 4, 3)


def test_unknown_define_warns_like_the_cli(repo):
    with pytest.warns(UserWarning, match=r'-D nope=1: .*furnace.xml has no <default name="nope">'):
        quadtri.render(repo / FURNACE, defines={"res": 2, "nope": 1})


def test_threads_do_not_change_the_image(repo):
    a = quadtri.render(repo / THESIS, spp=2, defines={"res": 16}, threads=1)
    b = quadtri.render(repo / THESIS, spp=2, defines={"res": 16}, threads=2)
    np.testing.assert_array_equal(a, b)


@pytest.mark.skipif(oiio is None, reason="needs Debian's python3-openimageio")
def test_spp_caps_an_adaptive_integrator_as_the_cli_does(cli, repo, tmp_path):
    """spp means what --spp means (RenderSettings): setup b's adaptive integrator (min_samples
    16, max_samples $spp) is capped at 4 samples per pixel, bit for bit the CLI's image."""
    scene = repo / "scenes/thesis/b-triangle.xml"
    exr = tmp_path / "cli.exr"
    out = cli("render", scene, "-D", "res=8", "--spp", 4, "--seed", 2, "-o", exr).stdout
    assert "8x8, 4.0 samples/pixel" in out
    img, stats = quadtri.render(scene, spp=4, seed=2, defines={"res": 8}, return_stats=True)
    assert stats["samples_per_pixel"] == 4.0
    assert "max=4" in stats["integrator"]
    np.testing.assert_array_equal(img, read_exr(exr))
