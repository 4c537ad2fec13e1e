"""Error of instant radiosity against the number of light paths N on the Cornell box.

Renders data/cornell_box.gltf with the raster and rt-vpl estimators at several N, compares each
image against a path-traced reference (irad.compare, relMSE over 4x4 blocks) and plots the error
against N into a PNG (matplotlib, Debian's python3-matplotlib).

Run from the repository root after scripts/setup.sh:
  PYTHONPATH=build/python /usr/bin/python3 python/examples/error_against_paths.py -o out/error.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import irad


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="error_against_paths.png")
    parser.add_argument("--scene", default="data/cornell_box.gltf")
    parser.add_argument("--size", type=int, default=96)
    parser.add_argument("--reference-spp", type=int, default=1024)
    args = parser.parse_args()

    scene = irad.load(args.scene)
    size = (args.size, args.size)
    reference, _ = irad.render(scene, size=size, estimator="pt", spp=args.reference_spp)
    paths = [4, 8, 16, 32, 64, 128, 256, 512]
    fig, ax = plt.subplots(figsize=(6, 4))
    for estimator in ["raster", "rt-vpl"]:
        errors = []
        for n in paths:
            image, _ = irad.render(scene, size=size, paths=n, estimator=estimator)
            errors.append(irad.compare(image, reference, block=4)["relmse"])
            print(f"{estimator} N={n}: relMSE {errors[-1]:.5f}")
        ax.loglog(paths, errors, "o-", label=estimator)
    ax.set_xlabel("light paths N")
    ax.set_ylabel(f"relMSE against pt ({args.reference_spp} spp), 4x4 blocks")
    ax.set_title(f"{args.scene}, {args.size}x{args.size}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
