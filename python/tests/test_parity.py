"""The package gives the command line's answers bit for bit (`revdist distance --batch`), and
its error messages."""

import json
import subprocess

import numpy as np
import pytest

import revdist
from conftest import random_poses

# (A, B, eps): exact models, freeform, analytic, a closed form and a morph frame.
PAIRS = [
    ("pawn", "cup", 1e-3),
    ("bottle", "pawn", 1e-4),
    ("cup_ff", "lightmill", 1e-3),
    ("ring", "cone", 1e-4),
    ("sphere", "ring", 1e-3),
    ("capsule", "morph@0.3", 1e-3),
]
PER_PAIR = 50
SEED = 20261127


def run_batch(cli, lines, *extra):
    """The command line's answers to JSON request `lines`, one dict per line."""
    text = "".join(json.dumps(line) + "\n" for line in lines)
    out = subprocess.run(
        [cli, "distance", "--batch", "-", *extra],
        input=text,
        capture_output=True,
        text=True,
        check=False,
    )
    assert out.returncode in (0, 1), out.stderr
    answers = [json.loads(line) for line in out.stdout.splitlines()]
    assert len(answers) == len(lines)
    return answers


def bits(x):
    return np.asarray(x, dtype=np.float64).view(np.uint64)


def test_bit_identical_to_the_cli_batch(cli):
    rng = np.random.default_rng(SEED)
    requests, expected = [], []
    for a, b, eps in PAIRS:
        # Close poses: about a third overlap or touch, the rest within a few sizes.
        poses = random_poses(rng, PER_PAIR, 1.2, digits=9)
        for p in poses:
            requests.append(
                {
                    "a": a,
                    "b": b,
                    "eps": eps,
                    "pose_b": {"translation": list(p[:3]), "rotation": list(p[3:])},
                }
            )
        expected.append((a, b, eps, poses))
    answers = run_batch(cli, requests)
    assert all("error" not in x for x in answers), [x for x in answers if "error" in x][:3]
    k, separated = 0, 0
    for a, b, eps, poses in expected:
        sa, sb = revdist.Solid.model(a, eps=eps), revdist.Solid.model(b, eps=eps)
        r = revdist.distance(sa, sb, poses)
        cli_part = answers[k : k + len(poses)]
        k += len(poses)
        for key, name in [("value", "distance"), ("lower", "lower"), ("upper", "upper")]:
            want = [x[name] for x in cli_part]
            assert np.array_equal(bits(getattr(r, key)), bits(want)), (a, b, key)
        for key in ("point_a", "point_b"):
            want = np.array([x[key] for x in cli_part])
            assert np.array_equal(bits(getattr(r, key)), bits(want)), (a, b, key)
        for key in ("overlap", "budget_exhausted", "closed_form", "width_limit"):
            assert list(getattr(r, key)) == [x[key] for x in cli_part], (a, b, key)
        for key in ("node_pairs", "leaf_bounds", "leaf_tests", "subdivided_pairs"):
            assert list(getattr(r, key)) == [x[key] for x in cli_part], (a, b, key)
        # The gradient: present exactly where the command line gives one, the same bits.
        for key, name in [("gradient_translation", "translation"), ("gradient_rotation", "rotation")]:
            got = getattr(r, key)
            for i, x in enumerate(cli_part):
                if x.get("gradient") is None:
                    assert np.isnan(got[i]).all(), (a, b, key, i)
                else:
                    assert np.array_equal(bits(got[i]), bits(x["gradient"][name])), (a, b, key, i)
        separated += sum(x.get("gradient") is not None for x in cli_part)
    # The campaign met every kind of answer it is meant to compare.
    assert k == len(PAIRS) * PER_PAIR
    assert 0 < separated < k, separated


def test_options_are_the_cli_options(cli):
    """tolerance and a node-pair budget map to the same query as the CLI's flags."""
    rng = np.random.default_rng(SEED + 1)
    poses = random_poses(rng, 20, 1.0, digits=9)
    lines = [
        {"a": "pawn", "b": "bottle", "eps": 1e-3, "tolerance": 0.0,
         "pose_b": {"translation": list(p[:3]), "rotation": list(p[3:])}}
        for p in poses
    ]
    answers = run_batch(cli, lines, "--max-node-pairs", "3")
    a, b = revdist.Solid.model("pawn", eps=1e-3), revdist.Solid.model("bottle", eps=1e-3)
    r = revdist.distance(a, b, poses, tolerance=0.0, max_node_pairs=3)
    assert np.array_equal(bits(r.lower), bits([x["lower"] for x in answers]))
    assert np.array_equal(bits(r.upper), bits([x["upper"] for x in answers]))
    assert list(r.budget_exhausted) == [x["budget_exhausted"] for x in answers]
    assert any(r.budget_exhausted)


def test_a_profile_file_is_the_model_it_was_exported_from(cli, tmp_path, pawn_cup):
    """`revdist export` writes a profile that reads back bit-identically: Solid.from_file
    (and Solid.load of the path) give the built-in model's answers."""
    path = tmp_path / "cup.toml"
    subprocess.run([cli, "export", "cup", "--toml", str(path)], check=True, capture_output=True)
    a, b = pawn_cup
    poses = random_poses(np.random.default_rng(SEED + 2), 20, 1.0)
    want = revdist.distance(a, b, poses)
    for solid in (revdist.Solid.from_file(path, eps=1e-3), revdist.Solid.load(str(path), eps=1e-3)):
        got = revdist.distance(a, solid, poses)
        assert np.array_equal(bits(got.lower), bits(want.lower))
        assert np.array_equal(bits(got.point_b), bits(want.point_b))


def cli_error(cli, request):
    (answer,) = run_batch(cli, [request])
    return answer["error"]


def test_errors_carry_the_cli_messages(cli, tmp_path, pawn_cup):
    a, b = pawn_cup
    # Non-unit quaternion: the CLI says "pose_b: <msg>", the package "poses[i]: <msg>".
    rot = [1.1, 0.0, 0.0, 0.0]
    msg = cli_error(cli, {"a": "pawn", "b": "cup", "pose_b": {"rotation": rot}})
    assert msg.startswith("pose_b: ")
    with pytest.raises(ValueError) as e:
        revdist.distance(a, b, np.array([[0, 0, 0, 1, 0, 0, 0], [0, 0, 0, *rot]], float))
    assert str(e.value) == "poses[1]: " + msg[len("pose_b: "):]
    # A quaternion typed with 4 decimals (norm 0.99999) is normalised by both, to the
    # same bits; one further off than 1e-3 is refused by both with its normalised value.
    typed = [0.7071, 0.0, 0.7071, 0.0]
    (answer,) = run_batch(cli, [{"a": "pawn", "b": "cup", "eps": 1e-3,
                                 "pose_b": {"translation": [1.5, 0.0, 0.2], "rotation": typed}}])
    got = revdist.distance(a, b, np.array([1.5, 0.0, 0.2, *typed]))
    assert (got.value, got.lower, got.upper) == (answer["distance"], answer["lower"], answer["upper"])
    unit = np.array(typed) / np.linalg.norm(typed)
    exact = revdist.distance(a, b, np.array([1.5, 0.0, 0.2, *unit]))
    assert abs(exact.value - got.value) < 1e-12
    rot = [0.7, 0.0, 0.7, 0.0]
    msg = cli_error(cli, {"a": "pawn", "b": "cup", "pose_b": {"rotation": rot}})
    assert msg.endswith("normalised it is [0.7071067811865476, 0.0, 0.7071067811865476, 0.0]")
    with pytest.raises(ValueError) as e:
        revdist.distance(a, b, np.array([0, 0, 0, *rot], float))
    assert str(e.value) == "poses: " + msg[len("pose_b: "):]
    # An unknown name, resolved as the CLI resolves it (name, else file).
    msg = cli_error(cli, {"a": "nope", "b": "cup"})
    with pytest.raises(FileNotFoundError) as e:
        revdist.Solid.load("nope")
    assert str(e.value) == msg
    with pytest.raises(ValueError) as e:
        revdist.Solid.model("nope")
    assert msg.startswith(str(e.value))
    # A file that is not a profile.
    bad = tmp_path / "bad.toml"
    bad.write_text("name = 3\n")
    msg = cli_error(cli, {"a": str(bad), "b": "cup"})
    for load in (revdist.Solid.from_file, revdist.Solid.load):
        with pytest.raises(ValueError) as e:
            load(str(bad))
        assert str(e.value) == msg
    with pytest.raises(FileNotFoundError, match="cannot read .*missing.toml"):
        revdist.Solid.from_file(str(tmp_path / "missing.toml"))
    # eps and tolerance.
    msg = cli_error(cli, {"a": "pawn", "b": "cup", "eps": -1.0})
    with pytest.raises(ValueError) as e:
        revdist.Solid.model("pawn", eps=-1.0)
    assert str(e.value) == msg
    msg = cli_error(cli, {"a": "pawn", "b": "cup", "tolerance": -0.5})
    with pytest.raises(ValueError) as e:
        revdist.distance(a, b, np.array([1.0, 0, 0, 1, 0, 0, 0]), tolerance=-0.5)
    assert str(e.value) == msg
    # A pose out of the representable range.
    far = [1e101, 0.0, 0.0]
    msg = cli_error(cli, {"a": "pawn", "b": "cup", "pose_b": {"translation": far}})
    assert msg.startswith("pose_b: ")
    with pytest.raises(ValueError) as e:
        revdist.distance(a, b, np.array([[*far, 1, 0, 0, 0]]))
    assert str(e.value) == "poses[0]: " + msg[len("pose_b: "):]
