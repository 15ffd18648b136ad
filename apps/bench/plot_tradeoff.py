#!/usr/bin/env python3
"""Plots `spatter-bench tradeoff --json` results: placement time per decal against the p99 distance of
the proxy hits to the render surface, one curve per backend, one panel per mesh.

    python3 apps/bench/plot_tradeoff.py docs/benchmarks/tradeoff-*.json --out docs/benchmarks/tradeoff.png

Needs matplotlib (Debian: python3-matplotlib). The render mesh (error 0) is drawn as a dashed line at
its placement time; the three.js peer's time per decal, far above, is written in the panel title.
"""

import argparse
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLORS = {"openmesh": "tab:blue", "meshopt": "tab:orange"}


def load(path):
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    if data.get("command") != "tradeoff" or not isinstance(data.get("rows"), list):
        raise ValueError(f"{path}: not the JSON of spatter-bench tradeoff")
    return data


def panel(ax, data):
    rows = [r for r in data["rows"] if r.get("status") == "ok"]
    render = [r for r in rows if r["backend"] == "render"]
    if render and render[0].get("placement_ns") is not None:
        ax.axhline(render[0]["placement_ns"], color="black", linestyle="--", linewidth=1,
                   label=f"render mesh ({render[0]['proxy_triangles']:,} tris)")
    for backend, color in COLORS.items():
        pts = sorted(
            (r for r in rows if r["backend"] == backend
             and r.get("dist_p99_rel") is not None and r.get("placement_ns") is not None),
            key=lambda r: r["tolerance_rel"])
        if not pts:
            continue
        xs = [max(100.0 * r["dist_p99_rel"], 1e-6) for r in pts]
        ys = [r["placement_ns"] for r in pts]
        ax.plot(xs, ys, marker="o", color=color, label=backend)
        for r, x, y in zip(pts, xs, ys):
            ax.annotate(f"{100 * r['tolerance_rel']:g}%", (x, y), textcoords="offset points", xytext=(4, 4),
                        fontsize=7, color=color)
    ax.set_xscale("log")
    ax.set_xlabel("p99 distance of proxy hits to the render surface (% of diagonal)")
    ax.set_ylabel("DecalSystem::spawn, ns per ray")
    title = f"{data['mesh']} ({data['render_triangles']:,} triangles)"
    for peer in data.get("peers", []):
        ns = peer.get("per_decal_ns")
        if ns:
            title += f"\nthree.js DecalGeometry: {ns / 1e6:.1f} ms per decal"
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json", nargs="+", help="spatter-bench tradeoff --json outputs")
    parser.add_argument("--out", default="docs/benchmarks/tradeoff.png", help="PNG to write")
    args = parser.parse_args()
    try:
        results = [load(p) for p in args.json]
    except (OSError, ValueError) as e:
        print(f"plot_tradeoff.py: {e}", file=sys.stderr)
        return 1
    cols = min(3, len(results))
    rows = math.ceil(len(results) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.2 * rows), squeeze=False)
    for ax, data in zip(axes.flat, results):
        panel(ax, data)
    for ax in list(axes.flat)[len(results):]:
        ax.axis("off")
    machine = results[0].get("machine", {}).get("cpu", "")
    fig.suptitle(f"Placement time against error (spatter-bench tradeoff; {machine})", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
