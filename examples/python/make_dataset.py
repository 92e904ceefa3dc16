"""A data set of face shapes: N random sparse activation vectors, each settled on a head (as
`myoshell pose`), saved in one .npz (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/make_dataset.py --n 200 --out faces.npz

The .npz holds activations (N, m) float64 in [0, 1], displacements (N, n, 3) float32 in cm (settled
shape minus rest), rest (n, 3) float64 cm, triangles (m_t, 3) int32 and muscle_names (m,) str.
"""
import argparse
import os

import numpy as np

import myoshell


def random_activations(rng, muscle_count, max_active, low, high):
    """One sparse vector: 1 to max_active muscles, each at a value drawn uniformly in [low, high]."""
    a = np.zeros(muscle_count)
    active = rng.choice(muscle_count, size=rng.integers(1, max_active + 1), replace=False)
    a[active] = rng.uniform(low, high, size=active.size)
    return a


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--n", type=int, default=200, help="number of shapes (default 200)")
    parser.add_argument("--out", default="dataset.npz", help="the .npz to write (default dataset.npz)")
    parser.add_argument("--head", default="default", help="'default', a head folder or an OBJ (then --landmarks)")
    parser.add_argument("--landmarks", default=None, help="landmark file of an OBJ head")
    parser.add_argument("--units", default="cm", help="the OBJ head's unit: m, mm or cm")
    parser.add_argument("--library", default="face", help="muscles: face (the whole face, the default), builtin or a library file")
    parser.add_argument("--max-active", type=int, default=3, help="at most this many muscles active per shape")
    parser.add_argument("--low", type=float, default=0.2, help="smallest activation of an active muscle")
    parser.add_argument("--high", type=float, default=1.0, help="largest activation of an active muscle")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--cache", default=os.environ.get("MYOSHELL_CACHE") or os.path.expanduser("~/.cache/myoshell"),
                        help="basis cache folder (default $MYOSHELL_CACHE or ~/.cache/myoshell)")
    args = parser.parse_args()
    if args.n < 1:
        parser.error("--n must be at least 1")
    if not 0.0 <= args.low <= args.high <= 1.0:
        parser.error("need 0 <= --low <= --high <= 1")

    head = myoshell.load_head(args.head, landmarks=args.landmarks, units=args.units)
    face = myoshell.Face(head, library=args.library, cache=args.cache)
    names = face.muscle_names
    rest = face.rest_positions()
    rng = np.random.default_rng(args.seed)
    activations = np.stack([random_activations(rng, len(names), min(args.max_active, len(names)), args.low, args.high)
                            for _ in range(args.n)])
    displacements = np.empty((args.n, rest.shape[0], 3), dtype=np.float32)
    for i, a in enumerate(activations):
        displacements[i] = face.pose(dict(zip(names, a))) - rest
    np.savez_compressed(args.out, activations=activations, displacements=displacements, rest=rest,
                        triangles=face.triangles(), muscle_names=np.array(names))
    print(f"wrote {args.out}: {args.n} shapes of {rest.shape[0]} vertices, {len(names)} muscles")


if __name__ == "__main__":
    main()
