"""Draws the extension's icon (icon.png, 128 x 128): a trapezoidal speed profile, the shape every
move of the three controllers follows, over the name. Run with the project's venv (matplotlib):
    .venv/bin/python editors/vscode/images/make_icon.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.patches import FancyBboxPatch

SIZE = 128
DPI = 64


def main() -> None:
    fig = plt.figure(figsize=(SIZE / DPI, SIZE / DPI), dpi=DPI)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.axis("off")
    ax.add_patch(FancyBboxPatch((0.04, 0.04), 0.92, 0.92, boxstyle="round,pad=0,rounding_size=0.16",
                                facecolor="#1f3a5f", edgecolor="none"))
    ax.plot([0.16, 0.34, 0.66, 0.84], [0.46, 0.80, 0.80, 0.46], color="#ffb000", linewidth=7,
            solid_capstyle="round", solid_joinstyle="round")
    ax.plot([0.12, 0.88], [0.46, 0.46], color="#9fb7d4", linewidth=2.5, solid_capstyle="round")
    ax.text(0.5, 0.22, "mcc", color="white", fontsize=25, fontweight="bold", ha="center", va="center",
            family="DejaVu Sans")
    fig.savefig(Path(__file__).with_name("icon.png"), dpi=DPI, transparent=True)


if __name__ == "__main__":
    main()
