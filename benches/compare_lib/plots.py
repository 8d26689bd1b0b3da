"""PNG plots beside compare.md and tradeoff.md (matplotlib, Agg backend)."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import peers  # noqa: E402

# The byte rule's level in a `--ours-mode cut` report, whose "ours" is the cut.
OURS_RULE_LABEL = "ours (byte rule)"
COLORS = {"ours": "tab:red", "ours-rule": "tab:orange", "coacd": "tab:blue", "coacd-paper": "tab:cyan", "vhacd": "tab:green"}


def label(m):
    return {"ours": "ours", "ours-rule": OURS_RULE_LABEL}.get(m) or peers.LABEL[m]


def slot(r, m):
    if m == "ours-rule":  # --ours-mode cut: the byte rule's level beside the cut
        return r.get("ours_rule", {})
    return r["ours"] if m == "ours" else r["peers"].get(m, {})


def grouped_bars(ax, records, methods, value, ylabel, floor=None):
    """Bars per mesh and method on a log axis; with `floor`, smaller values (round-off
    on exact colliders) are drawn at the floor."""
    width = 0.8 / max(1, len(methods))
    for i, m in enumerate(methods):
        xs, ys = [], []
        for j, r in enumerate(records):
            v = value(slot(r, m))
            if v is not None and (v > 0 or floor):
                xs.append(j + (i - (len(methods) - 1) / 2) * width)
                ys.append(max(v, floor) if floor else v)
        ax.bar(xs, ys, width=width, label=label(m), color=COLORS.get(m))
    ax.set_yscale("log")
    ax.set_ylabel(ylabel)
    ax.set_xticks(range(len(records)))
    ax.set_xticklabels([r["mesh"] for r in records], rotation=90, fontsize=6)
    ax.grid(axis="y", alpha=0.3)


def metric(key):
    return lambda s: (s.get("metrics") or {}).get(key)


def compare_plots(records, methods, out, name="compare"):
    """OUT/NAME_distance.png, OUT/NAME_bytes.png and OUT/NAME_seconds.png."""
    rs = [r for r in records if r["ours"].get("metrics")]
    if not rs:
        return
    w = max(8, 0.35 * len(rs))
    fig, axes = plt.subplots(2, 1, figsize=(w, 8), constrained_layout=True)
    grouped_bars(axes[0], rs, methods, metric("hausdorff"), "Hausdorff / diagonal (floor 1e-6)", 1e-6)
    grouped_bars(axes[1], rs, methods, metric("chamfer"), "Chamfer / diagonal (floor 1e-7)", 1e-7)
    axes[0].legend(fontsize=8)
    axes[0].set_title("Distance from collider to input, per mesh (lower is closer)")
    fig.savefig(out / f"{name}_distance.png", dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(w, 4.5), constrained_layout=True)
    grouped_bars(ax, rs, methods, lambda s: s.get("bytes"), "bytes (paper Table 2)")
    ax.legend(fontsize=8)
    ax.set_title("Collider size per mesh")
    fig.savefig(out / f"{name}_bytes.png", dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 5), constrained_layout=True)
    for m in methods:
        pts = [(r.get("faces"), slot(r, m).get("seconds")) for r in records]
        pts = [(f, s) for f, s in pts if f and s and s > 0]
        if pts:
            ax.scatter(*zip(*pts), label=label(m), color=COLORS.get(m), s=14)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("input faces")
    ax.set_ylabel("seconds")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Time against input size (peers: 1 thread; ours: 1 thread)")
    fig.savefig(out / f"{name}_seconds.png", dpi=110)
    plt.close(fig)
