"""Per-pose cost of `revdist.distance` against the core's Rust batch API, and the speed-up
of a 10,000-pose call on two threads.

    python python/bench/overhead.py        # after maturin develop --release
    cargo run --release --manifest-path python/Cargo.toml --example rust_batch

Two far-apart spheres (closed form, well under a microsecond each) isolate the per-pose
overhead; pawn/cup at close poses give the speed-up of real queries. The best of several
runs is reported (the least disturbed by other processes).
"""

import time

import numpy as np

import revdist

REPS = 30
N = 10_000


def best(f, reps=REPS):
    t = []
    for _ in range(reps):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def main():
    sphere = revdist.Solid.model("sphere", eps=1e-4)
    far = np.zeros((N, 7))
    far[:, 0] = 10.0 + np.arange(N) * 1e-4
    far[:, 3] = 1.0
    r = revdist.distance(sphere, sphere, far, threads=1)
    assert r.closed_form.all()
    for threads in (1, 2):
        t = best(lambda: revdist.distance(sphere, sphere, far, threads=threads))
        print(f"python, far spheres, N = {N}, {threads} thread(s): {t / N * 1e6:.3f} us/pose")
    a, b = revdist.Solid.model("pawn", eps=1e-4), revdist.Solid.model("cup", eps=1e-4)
    rng = np.random.default_rng(5)
    poses = np.hstack([rng.uniform(-1.2, 1.2, (N, 3)), rng.normal(size=(N, 4))])
    poses[:, 3:] /= np.linalg.norm(poses[:, 3:], axis=1)[:, None]
    times = {k: best(lambda: revdist.distance(a, b, poses, threads=k), reps=3) for k in (1, 2)}
    print(
        f"python, pawn/cup close poses, N = {N}: 1 thread {times[1]:.3f} s, 2 threads "
        f"{times[2]:.3f} s, speed-up {times[1] / times[2]:.2f}x"
    )


if __name__ == "__main__":
    main()
