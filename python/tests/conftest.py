"""Shared fixtures of the Python package's tests: the command-line binary the parity tests
compare with, and seeded poses."""

import os
import pathlib
import shutil

import numpy as np
import pytest

import revdist

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    """The `revdist` binary: $REVDIST_CLI (set by scripts/python-test.sh), else the release
    build under $CARGO_TARGET_DIR or target/."""
    candidates = [os.environ.get("REVDIST_CLI")]
    target = os.environ.get("CARGO_TARGET_DIR", str(ROOT / "target"))
    candidates.append(str(pathlib.Path(target) / "release" / "revdist"))
    candidates.append(shutil.which("revdist"))
    for c in candidates:
        if c and pathlib.Path(c).is_file():
            return c
    pytest.fail(
        "no revdist binary: build it with `cargo build --release --bin revdist` or set REVDIST_CLI"
    )


def random_poses(rng, n, spread, digits=None):
    """`n` poses `[tx, ty, tz, qw, qx, qy, qz]`: translations uniform in a cube of half-side
    `spread`, rotations uniform (normalised Gaussian quaternions). With `digits`, every
    number is rounded to that many decimals, so that its decimal text parses to the same
    double in Python and in the command line's JSON reader."""
    t = rng.uniform(-spread, spread, (n, 3))
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    poses = np.hstack([t, q])
    if digits is not None:
        poses = np.round(poses, digits)
    return poses


@pytest.fixture(scope="session")
def pawn_cup():
    return revdist.Solid.model("pawn", eps=1e-3), revdist.Solid.model("cup", eps=1e-3)
