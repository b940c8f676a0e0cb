"""Camera images as NumPy arrays: sim.image's read-only views that change in place at each
frame, and sim.render's new arrays from a free view or from a camera's pose, with the
arguments refused by name. Drawn headless (EGL; no display server)."""

import os

import numpy as np
import pytest

os.environ.pop("DISPLAY", None)

import s2sim  # noqa: E402

SOURCE = os.environ.get("S2SIM_SOURCE_DIR", os.getcwd())
SCENE = os.path.join(SOURCE, "python", "examples", "seek_target")
CAMERA = "robots/seeker/sensors/eye"
RIGHT, LEFT = "robots/seeker/axes/right/ref_voltage", "robots/seeker/axes/left/ref_voltage"
TARGET = (1.0, 0.0)  # the post's centre; 0.12 m square, 0.25 m tall


@pytest.fixture
def sim():
    return s2sim.Simulation(SCENE, defines={"target_x": TARGET[0], "target_y": TARGET[1]})


def test_image_is_a_read_only_view_that_changes_in_place(sim):
    name = CAMERA + "/rgb"
    assert sim.image_names == [name]
    image = sim.image(name)
    assert image.shape == (60, 80, 3) and image.dtype == np.uint8
    assert sim.image_frame(name) == 0 and not image.any()  # no frame yet
    with pytest.raises(ValueError):
        image[0, 0, 0] = 1
    assert not image.flags.writeable

    sim.step(1)
    assert sim.image_frame(name) == 1
    first = np.array(image)  # a copy keeps the frame
    r, g = first[..., 0].astype(int), first[..., 1].astype(int)
    red = (r > 50) & (r > 2 * g)
    assert red[:, 35:45].any() and not red[:, :20].any()  # the post straight ahead
    sim.set_input(RIGHT, 6.0)  # turn on the spot: the post slides right across the image
    sim.set_input(LEFT, 6.0)
    sim.step(int(round(0.2 / sim.tick_s)))
    assert sim.image_frame(name) > 1
    assert not np.array_equal(image, first)  # the same array, new pixels
    assert sim.image(name).__array_interface__["data"] == image.__array_interface__["data"]


def test_render_from_a_camera_draws_what_the_camera_sees(sim):
    with pytest.raises(s2sim.UsageError, match="camera.*no frame yet"):
        sim.render(camera=CAMERA)
    sim.step(1)
    seen = sim.render(camera=CAMERA)
    assert seen.shape == (60, 80, 3) and seen.dtype == np.uint8
    assert seen.flags.writeable and seen.flags.owndata  # new, not a view
    difference = np.abs(seen.astype(int) - sim.image(CAMERA + "/rgb"))
    assert difference.mean() < 0.5 and difference.max() <= 8
    # The camera's optics at another size: the same picture, sampled finer.
    big = sim.render(camera=CAMERA, width=160, height=120)
    assert big.shape == (120, 160, 3)
    assert np.abs(big[::2, ::2].astype(int) - seen).mean() < 12


def test_render_free_view_outputs_depth_and_segmentation(sim):
    eye = (TARGET[0] - 1.0, TARGET[1], 0.125)
    rgb, depth, ids = sim.render(eye=eye, target=(TARGET[0], TARGET[1], 0.125), width=64,
                                 height=48, fov=40, outputs=("rgb", "depth", "segmentation"))
    assert rgb.shape == (48, 64, 3) and rgb.dtype == np.uint8
    assert depth.shape == (48, 64) and depth.dtype == np.float32
    assert ids.shape == (48, 64) and ids.dtype == np.uint16
    centre = (24, 32)
    assert depth[centre] == pytest.approx(1.0 - 0.06, abs=0.01)  # the post's near face
    assert ids[centre] == 0  # an obstacle: the world
    assert ids[0, 32] == 65535 and np.isinf(depth[0, 32])  # the sky
    assert int(rgb[centre][0]) > 2 * int(rgb[centre][1])  # red
    # One output alone is an array; a tuple keeps the order asked.
    only = sim.render(eye=eye, target=(1, 0, 0.125), width=64, height=48, fov=40,
                      outputs="depth")
    assert only.shape == (48, 64) and np.array_equal(only, depth)
    d, c = sim.render(eye=eye, target=(1, 0, 0.125), width=64, height=48, fov=40,
                      outputs=["depth", "rgb"])
    assert np.array_equal(d, depth) and np.array_equal(c, rgb)
    # Looking down at the robot from above: its bodies' indices.
    top = sim.render(eye=(0, 0, 1.5), target=(0, 0, 0), up=(1, 0, 0), outputs="segmentation")
    robot = {sim.body_names().index(n) for n in sim.body_names() if n.startswith("robots/")}
    assert robot & set(np.unique(top).tolist())


@pytest.mark.parametrize("kwargs, argument", [
    (dict(), "eye"),
    (dict(eye=(0, 0, 1)), "target"),
    (dict(eye=(0, 0, 1), target=(0, 0, 1)), "target"),
    (dict(eye=(0, 0, 1), target=(0, 0, 0)), "up"),
    (dict(eye=(0, 1), target=(0, 0, 0)), "eye"),
    (dict(eye="here", target=(0, 0, 0)), "eye"),
    (dict(eye=(0, 0, 1), target=(1, 0, float("nan"))), "target"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), fov=180), "fov"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), fov="wide"), "fov"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), width=0), "width"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), height=2.5), "height"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), width=16384, height=16384), "width"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), near=0), "near"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), near=2, far=1), "far"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), far=float("inf")), "far"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), outputs="colour"), "outputs"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), outputs=()), "outputs"),
    (dict(eye=(0, 0, 1), target=(1, 0, 0), outputs=("rgb", "rgb")), "outputs"),
    (dict(camera="robots/seeker/sensors/nose"), "camera"),
    (dict(camera=CAMERA, eye=(0, 0, 1), target=(1, 0, 0)), "camera"),
    (dict(camera=3), "camera"),
])
def test_render_refuses_bad_arguments_by_name(sim, kwargs, argument):
    with pytest.raises(s2sim.UsageError, match=r"^render\(\): " + argument + " "):
        sim.render(**kwargs)


def test_unknown_camera_lists_the_cameras(sim):
    with pytest.raises(s2sim.UsageError, match="cameras: " + CAMERA):
        sim.render(camera="eye")


def test_render_between_steps_leaves_the_run_as_it_was():
    def drive(render):
        sim = s2sim.Simulation(SCENE, defines={"target_x": TARGET[0], "target_y": TARGET[1]})
        sim.set_input(RIGHT, 5.0)
        sim.set_input(LEFT, -4.0)
        frames = []
        for _ in range(10):
            sim.step(40)
            if render:
                sim.render(eye=(-1, -1, 1), target=(0, 0, 0), outputs=("rgb", "depth"))
                sim.render(camera=CAMERA, width=32, height=24)
            frames.append(np.array(sim.image(CAMERA + "/rgb")))
        return np.array(sim.body_positions), frames

    plain, plain_frames = drive(False)
    rendered, rendered_frames = drive(True)
    assert np.array_equal(plain, rendered)  # bit for bit
    assert all(np.array_equal(a, b) for a, b in zip(plain_frames, rendered_frames))
