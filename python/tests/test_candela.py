"""The Python module candela: its arrays are the command line's PFM byte for byte, its
errors carry the command line's file:line:column messages, Ctrl-C cancels a render, and compare,
probe, write_image/read_image and the radiosity solution give what their commands give.

Run by ctest (Python.Pytest) with PYTHONPATH=build/python, CANDELA_CLI=the built command line and
CANDELA_SOURCE_DIR=the checkout; Debian's /usr/bin/python3 with python3-numpy and python3-pytest.
"""
import json
import os
import pathlib
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import candela

SOURCE = pathlib.Path(os.environ.get("CANDELA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("CANDELA_CLI", str(SOURCE / "build" / "cli" / "candela"))
CORNELL = str(SOURCE / "scenes" / "cornell-box.json")
SMALL = {"camera.width": 32, "camera.height": 24}


def read_pfm(path):
    """A colour PFM (little-endian, scale -1) as float32 (height, width, 3), row 0 at the top."""
    data = pathlib.Path(path).read_bytes()
    header, _, rest = data.partition(b"\n")
    assert header == b"PF"
    size, _, rest = rest.partition(b"\n")
    scale, _, pixels = rest.partition(b"\n")
    width, height = map(int, size.split())
    assert float(scale) < 0  # little-endian
    rows = np.frombuffer(pixels, dtype="<f4").reshape(height, width, 3)
    return rows[::-1]


def cli_render(tmp_path, method, extra=()):
    out = tmp_path / f"{method}.pfm"
    subprocess.run([CLI, "render", CORNELL, "--method", method, "-o", str(out), "-q",
                    "--set", "camera.width=32", "--set", "camera.height=24", *extra], check=True)
    return read_pfm(out)


@pytest.mark.parametrize("method, spp", [("radiosity", None), ("path", 4), ("whitted", None), ("raster", None),
                                         ("whitted", 4), ("raster", 9)])
def test_render_is_the_command_lines_pfm_byte_for_byte(tmp_path, method, spp):
    scene = candela.load_file(CORNELL, **SMALL)
    assert (scene.width, scene.height, scene.method) == (32, 24, "radiosity")
    image = candela.render(scene, method=method, spp=spp, threads=2)
    assert image.shape == (24, 32, 3) and image.dtype == np.float32
    reference = cli_render(tmp_path, method, ["--spp", str(spp)] if spp else [])
    assert image.tobytes() == np.ascontiguousarray(reference).tobytes()
    assert image.max() > 0


def test_images_do_not_depend_on_the_thread_count_and_the_seed_is_the_renders():
    scene = candela.load_file(CORNELL, **SMALL)
    one = candela.render(scene, method="path", spp=2, threads=1)
    two = candela.render(scene, method="path", spp=2, threads=2)
    assert one.tobytes() == two.tobytes()
    other_seed = candela.render(scene, method="path", spp=2, seed=7)
    assert other_seed.tobytes() != one.tobytes()
    # The seed was this render's alone: the scene's own is back.
    assert candela.render(scene, method="path", spp=2).tobytes() == one.tobytes()
    # So are the anti-aliasing samples spp gave another method.
    plain = candela.render(scene, method="whitted")
    assert candela.render(scene, method="whitted", spp=4).tobytes() != plain.tobytes()
    assert candela.render(scene, method="whitted").tobytes() == plain.tobytes()


def test_bad_input_raises_input_error_with_the_location(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "candela/1",\n  "camera": {"eye": [0, 0, 5], "target": [0, 0, 0]},\n'
                   '  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}\n')
    with pytest.raises(candela.InputError) as caught:
        candela.load_file(str(bad))
    error = caught.value
    assert isinstance(error, ValueError)
    assert error.file == str(bad) and error.line == 3 and error.json_path == "shapes[0].radius"
    assert str(error).startswith(f"{bad}:3:")
    # An override is located at its --set, as on the command line.
    with pytest.raises(candela.InputError, match="camera.width"):
        candela.load_file(CORNELL, **{"camera.width": -4})
    with pytest.raises(candela.InputError):
        candela.load_file(str(tmp_path / "missing.json"))
    scene = candela.load_file(CORNELL, **SMALL)
    with pytest.raises(ValueError, match="unknown method 'teleport'"):
        candela.render(scene, method="teleport")
    with pytest.raises(ValueError, match="spp 5: whitted takes n×n samples per pixel"):
        candela.render(scene, method="whitted", spp=5)


def test_ctrl_c_cancels_a_render_and_the_next_one_runs():
    scene = candela.load_file(CORNELL, **{"camera.width": 256, "camera.height": 256})
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        candela.render(scene, method="path", spp=100000)
    assert time.monotonic() - start < 30
    small = candela.load_file(CORNELL, **SMALL)
    assert candela.render(small, method="path", spp=1).max() > 0


def test_write_and_read_image_round_trip(tmp_path):
    scene = candela.load_file(CORNELL, **SMALL)
    image = candela.render(scene, method="whitted")
    for name in ["a.pfm", "a.exr"]:
        candela.write_image(str(tmp_path / name), image)
        assert candela.read_image(str(tmp_path / name)).tobytes() == image.tobytes()
    candela.write_image(str(tmp_path / "a.png"), image)
    assert (tmp_path / "a.png").stat().st_size > 0
    with pytest.raises(ValueError, match="extension"):
        candela.write_image(str(tmp_path / "a.txt"), image)
    with pytest.raises(ValueError, match="shape"):
        candela.write_image(str(tmp_path / "b.pfm"), np.zeros((4, 4, 2)))


def test_compare_gives_the_command_lines_metrics(tmp_path):
    scene = candela.load_file(CORNELL, **SMALL)
    a = candela.render(scene, method="path", spp=2)
    b = candela.render(scene, method="path", spp=8)
    metrics = candela.compare(a, b)
    candela.write_image(str(tmp_path / "a.pfm"), a)
    candela.write_image(str(tmp_path / "b.pfm"), b)
    subprocess.run([CLI, "compare", str(tmp_path / "a.pfm"), str(tmp_path / "b.pfm"), "--json",
                    str(tmp_path / "m.json")], check=True, stdout=subprocess.DEVNULL)
    expected = json.loads((tmp_path / "m.json").read_text())
    for key in ["rmse", "relative_mse", "psnr_db", "mean_absolute_error", "max_absolute_error",
                "mean_luminance", "mean_luminance_reference", "luminance_ratio", "pixels_compared"]:
        assert metrics[key] == pytest.approx(expected[key], rel=1e-12), key
    assert metrics["max_absolute_error_at"] == expected["max_absolute_error_at"]
    difference = (a.astype(np.float64) - b) ** 2
    assert metrics["rmse"] == pytest.approx(np.sqrt(difference.mean()), rel=1e-9)
    # A mask: only its pixels count.
    mask = np.zeros(a.shape[:2], dtype=bool)
    mask[:, :16] = True
    masked = candela.compare(a, b, mask=mask)
    assert masked["pixels_compared"] == 24 * 16
    assert masked["rmse"] == pytest.approx(np.sqrt(difference[:, :16].mean()), rel=1e-9)
    identical = candela.compare(a, a)
    assert identical["rmse"] == 0 and identical["psnr_db"] == float("inf")


def test_probe_matches_an_emitting_square_and_the_solutions_have_their_mesh_and_sites(tmp_path):
    square = tmp_path / "lamp.json"
    square.write_text(json.dumps({
        "format": "candela/1",
        "camera": {"eye": [0, -1, 0], "target": [0, 1, 0], "up": [0, 0, -1], "width": 8, "height": 8},
        "radiosity": {"patch_size": 0.5},
        "shapes": [{"type": "quad", "corner": [-1, 1, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2],
                    "material": {"kd": 0.5, "emission": 3}}]}))
    scene = candela.load_file(str(square))
    # Under the centre of a 2 × 2 emitter of exitance 3, one unit away: E = 3 × 4 F(1, 1, 1),
    # F = 0.13853 the factor to each unit square's corner.
    corner = 0.138528
    for method in ["path", "radiosity"]:
        result = candela.probe(scene, [[0, 0, 0]], [[0, 1, 0]], method=method, samples=4096)
        assert result["irradiance"].shape == (1, 3)
        assert result["irradiance"][0] == pytest.approx([12 * corner] * 3, rel=0.01), method
        assert result["irradiance_standard_error"].shape == (1,)
    with pytest.raises(ValueError, match="normals"):
        candela.probe(scene, [[0, 0, 0]], [[0, 0, 0]])
    solution = candela.solution(scene, "radiosity")
    vertices, faces, radiosity = solution["vertices"], solution["faces"], solution["radiosity"]
    assert vertices.shape[1] == 3 and faces.shape[1] == 3 and radiosity.shape == vertices.shape
    assert faces.max() < len(vertices)
    # Alone in the scene the square emits and receives nothing: B = E = 3 at every vertex, on y = 1.
    assert np.allclose(radiosity, 3) and np.allclose(vertices[:, 1], 1)
    # The meshless solution at its sites: on the square, their effective areas summing to its 4 m²;
    # alone, it receives nothing, so λ (reflected light) and η (its direct part) are 0.
    sites = candela.solution(scene, "meshless")
    count = len(sites["area"])
    assert count > 100 and sites["positions"].shape == (count, 3) and sites["normals"].shape == (count, 3)
    assert sites["radiosity"].shape == (count, 3) and sites["direct"].shape == (count, 3)
    assert np.allclose(sites["positions"][:, 1], 1) and np.allclose(np.abs(sites["normals"][:, 1]), 1)
    assert sites["area"].sum() == pytest.approx(4, rel=1e-9)
    assert sites["object"].dtype == np.uint32 and np.all(sites["object"] == 0) and sites["facts"]["converged"]
    assert np.allclose(sites["radiosity"], 0) and np.allclose(sites["direct"], 0)
    # The solve's facts come along; a method with no view-independent solution is refused by name.
    assert solution["facts"]["elements"] == len(faces)
    with pytest.raises(ValueError, match="'path' has no view-independent solution .*radiosity, meshless"):
        candela.solution(scene, "path")


# render passes its seed and anti-aliasing samples down instead of setting them on the
# Scene, so Python threads rendering one Scene at once (the GIL is released while they run) each get
# the image the same render gives alone, and the Scene is as it was afterwards. Before, they took
# each other's seed and aa.n, and the Scene kept one of them.
def test_threads_rendering_one_scene_get_the_images_of_the_same_renders_alone():
    scene = candela.load_file(CORNELL, **SMALL)
    jobs = [("path", 1, 3), ("path", 4, 11), ("whitted", 4, 5), ("whitted", 9, None), ("raster", None, None),
            ("raster", 4, 7)]
    before = {"path": candela.render(scene, method="path", spp=2),
              "whitted": candela.render(scene, method="whitted"),
              "raster": candela.render(scene, method="raster")}
    alone = [candela.render(scene, method=method, spp=spp, seed=seed, threads=1) for method, spp, seed in jobs]
    threads, rounds = 3, 3
    start = threading.Barrier(threads)
    results = [[] for _ in range(threads)]
    errors = []

    def worker(index):
        try:
            start.wait()
            for round_ in range(rounds):
                # Each thread takes the jobs in its own order, so that different renders overlap.
                for k in range(len(jobs)):
                    job = (k * (index + 1) + round_) % len(jobs)
                    method, spp, seed = jobs[job]
                    results[index].append((job, candela.render(scene, method=method, spp=spp, seed=seed,
                                                               threads=1)))
        except BaseException as error:  # noqa: BLE001 - reported below, in the test's thread
            errors.append(error)

    workers = [threading.Thread(target=worker, args=(i,)) for i in range(threads)]
    for thread in workers:
        thread.start()
    for thread in workers:
        thread.join()
    assert not errors
    differing = [(jobs[job], index) for index in range(threads) for job, image in results[index]
                 if not np.array_equal(image, alone[job])]
    assert sum(len(r) for r in results) == threads * rounds * len(jobs)
    assert not differing, f"{len(differing)} of {threads * rounds * len(jobs)} images differ: {differing[:5]}"
    # The seed and the samples were the renders' alone: the Scene renders as before.
    for method, image in before.items():
        again = candela.render(scene, method=method, spp=2 if method == "path" else None)
        assert np.array_equal(again, image), method
    # And the seeds and samples matter, so the comparison above could fail.
    assert not np.array_equal(alone[0], alone[1]) and not np.array_equal(alone[2], alone[3])
    assert not np.array_equal(alone[4], alone[5])


# probe refuses what `candela probe --points` refuses — a point or a normal that is not
# finite (it returned zeros) — naming the index; a huge but finite normal has its direction.
def test_probe_refuses_points_and_normals_that_are_not_finite(tmp_path):
    scene = candela.load_file(CORNELL, **SMALL)
    good = [[0, 0.5, 0], [0.1, 0.5, 0.1]]
    up = [[0, 1, 0], [0, 1, 0]]
    for bad in [float("nan"), float("inf"), -float("inf")]:
        points = [list(p) for p in good]
        points[1][2] = bad
        with pytest.raises(ValueError, match=r"points\[1\]"):
            candela.probe(scene, points, up, samples=4)
        normals = [list(n) for n in up]
        normals[1][0] = bad
        with pytest.raises(ValueError, match=r"normals\[1\]"):
            candela.probe(scene, good, normals, samples=4)
    with pytest.raises(ValueError, match=r"normals\[0\]"):
        candela.probe(scene, good, [[0, 0, 0], [0, 1, 0]], samples=4)
    # (0, 1e300, 0) is the direction (0, 1, 0), as the command line's direction_of makes it.
    plain = candela.probe(scene, good, up, samples=16)
    huge = candela.probe(scene, good, [[0, 1e300, 0], [0, 1e300, 0]], samples=16)
    assert np.array_equal(plain["irradiance"], huge["irradiance"])


# compare refuses a value no image file holds — NaN, ±inf, or beyond the float range
# (±1e308, whose square overflows) — naming the array, the pixel and the value, rather than
# returning NaN or None metrics and a max error of -1.
@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf"), 1e308, -1e308])
@pytest.mark.parametrize("which", ["image", "reference"])
def test_compare_refuses_values_that_are_not_finite_or_beyond_the_float_range(value, which):
    a = np.full((4, 6, 3), 0.5)
    b = np.full((4, 6, 3), 0.25)
    bad = a.copy() if which == "image" else b.copy()
    bad[3, 5, 1] = value
    image, reference = (bad, b) if which == "image" else (a, bad)
    with pytest.raises(ValueError, match=rf"{which}: pixel \(5, 3\)") as caught:
        candela.compare(image, reference)
    assert ("nan" if value != value else "inf" if abs(value) == float("inf") else "1e+308") in str(caught.value)
    # Within the float range the metrics are finite.
    bad[3, 5, 1] = 3e38
    image, reference = (bad, b) if which == "image" else (a, bad)
    metrics = candela.compare(image, reference)
    assert np.isfinite(metrics["rmse"]) and metrics["max_absolute_error"] > 1e38


def test_renders_and_probes_that_would_hold_more_than_the_memory_limit_raise_before_any_work():
    """The command line's refusal, from Python too (render.memory_limit_mib)."""
    scene = candela.load_file(CORNELL, **{"camera.width": 4000, "camera.height": 3000,
                                          "render.memory_limit_mib": 100})
    for method in ("local", "raster", "path"):
        with pytest.raises(candela.InputError, match=f"{method} would hold .* more than the 100.0 MiB"):
            candela.render(scene, method=method)
    # A meshless probe solves first: its sites and effective areas are counted before the solve.
    tight = candela.load_file(CORNELL, **SMALL, **{"render.memory_limit_mib": 1})
    with pytest.raises(candela.InputError, match="meshless would hold .*up to 50000 sites"):
        candela.probe(tight, np.array([[0.0, 0.01, 0.0]]), np.array([[0.0, 1.0, 0.0]]), method="meshless")
