"""Image media from Python: a numpy array as a medium, the program's numbers for the same image
file, pickling, and refusals that name the argument."""
import copy
import os
import pickle
import subprocess

import numpy as np
import pandas as pd
import pytest

import softdrop

CLI = os.environ["SOFTDROP_CLI"]


def ramp(rows=80, columns=120):
    """A box of 120 x 80 pixels, a ramp of solid falling from the left to two thirds across."""
    y, x = np.mgrid[0:rows, 0:columns]
    height = rows - 1 - y  # rows from the top
    return ~((x < 80) & (np.abs(height - (60 - 0.4 * x)) < 4))


def test_an_array_is_a_medium_that_simulate_takes_as_the_program_takes_its_file(tmp_path):
    image = ramp()
    medium = softdrop.Medium.from_image(image, pixel_size=0.5, periodic=False)
    assert (medium.width, medium.height, medium.periodic, medium.pixel_size) == (60.0, 40.0, False, 0.5)
    assert len(medium) == 0 and medium.grains.shape == (0, 3)
    assert np.array_equal(medium.image, image) and np.array_equal(medium.to_image(120), image)
    assert medium.porosity() == image.mean()
    path = tmp_path / "ramp.png"
    medium.save(path)
    assert softdrop.Medium.load(path, pixel_size=0.5, periodic=False) == medium
    assert softdrop.Medium.load(path) != medium  # pixels of 1, periodic
    runs = tmp_path / "runs.csv"
    subprocess.run([CLI, "simulate", "--medium", str(path), "--pixel-size", "0.5", "--walls", "--droplets", "4",
                    "--seed", "3", "--quiet", "--runs", str(runs)], check=True, capture_output=True)
    program = pd.read_csv(runs, float_precision="round_trip")
    frame = softdrop.simulate_many(medium, 4, seed=3)
    for column in ["start_x", "tortuosity", "steps", "touched"]:
        pd.testing.assert_series_equal(frame[column], program[column], check_dtype=False, check_exact=True)
    one = softdrop.simulate(medium, x0=15.0)
    assert one.outcome == "passed" and one.tortuosity > 1.1 and list(one.touched_grains) == [0]


def test_an_image_medium_pickles_copies_and_prints():
    medium = softdrop.Medium.from_image(ramp(), pixel_size=0.25)
    for again in (pickle.loads(pickle.dumps(medium)), copy.deepcopy(medium)):
        assert again == medium and again.pixel_size == 0.25
    assert repr(medium) == "<softdrop.Medium: image of 120 x 80 pixels, 30.0 x 20.0, periodic>"
    assert softdrop.Medium.generate().image is None and softdrop.Medium.generate().pixel_size is None


def test_a_bad_image_raises_value_error_naming_it(tmp_path):
    with pytest.raises(ValueError, match="image: not binary"):
        softdrop.Medium.from_image(np.full((4, 4), 0.5))
    with pytest.raises(ValueError, match="image: a 2D array"):
        softdrop.Medium.from_image(np.ones((2, 2, 2), bool))
    with pytest.raises(ValueError, match="image: no pore pixel"):
        softdrop.Medium.from_image(np.zeros((4, 4), bool))
    with pytest.raises(ValueError, match="pixel_size = -1.0"):
        softdrop.Medium.from_image(np.ones((4, 4), bool), pixel_size=-1)
    with pytest.raises(FileNotFoundError, match="image '.*none.npy': no such file"):
        softdrop.Medium.load(tmp_path / "none.npy")
    np.save(tmp_path / "three.npy", np.array([[0, 1], [2, 1]]))
    with pytest.raises(RuntimeError, match="three.npy': not a binary image"):
        softdrop.Medium.load(tmp_path / "three.npy")
