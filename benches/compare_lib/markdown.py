"""The text of docs/results/compare.md."""

import datetime

from . import peers
from .noise import step_spread
from .plots import OURS_RULE_LABEL
from .report import CUT_RULE, RULE, machine, mean, median, metrics_of, slot, summary_rows

KIND_LETTER = [("box", "b"), ("sphere", "s"), ("capsule", "c"), ("cylinder", "y"), ("frustum", "f"), ("prism", "p")]


def label(m):
    return {"ours": "ours", "ours-rule": OURS_RULE_LABEL}.get(m) or peers.LABEL[m]


def fmt(x, spec):
    return "–" if x is None else format(x, spec)


def kinds(counts):
    return " ".join(f"{counts[k]}{c}" for k, c in KIND_LETTER if counts.get(k))


def summary_table(records, methods):
    common, rows = summary_rows(records, methods)
    lines = [
        f"Over the {len(common)} meshes where {', '.join(label(m) for m in methods)} all have results "
        "(distances over the input's AABB diagonal; wins count ties, within 1e-9, for every method tied):",
        "",
        "| method | Hausdorff wins | Chamfer wins | mean Hausdorff | median Hausdorff | mean Chamfer | median Chamfer | mean bytes | median bytes | mean s | median s | min enclosure |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        lines.append(
            f"| {label(r['method'])} | {r['wins_h']} | {r['wins_c']} | {mean(r['h']):.4f} | {median(r['h']):.4f} | "
            f"{mean(r['c']):.3e} | {median(r['c']):.3e} | {mean(r['b']):,.0f} | {median(r['b']):,.0f} | "
            f"{mean(r['s']):.2f} | {median(r['s']):.2f} | {min(r['e'], default=float('nan')):.6f} |"
        )
    return common, rows, lines


def targets_check(records, rows, methods):
    """The issue's targets for the engine, met or not, with the numbers."""
    by = {r["method"]: r for r in rows}
    o = by.get("ours")
    out = ["## The engine against the issue's targets", ""]
    if not o or not o["h"]:
        return out + ["No mesh has results for every method yet.", ""]
    for m in [m for m in methods if m != "ours"]:
        p = by[m]
        for key, name in (("h", "Hausdorff"), ("c", "Chamfer")):
            for fn, fname in ((mean, "mean"), (median, "median")):
                ok = fn(o[key]) < fn(p[key])
                out.append(f"- {fname} {name} below {label(m)}'s: {'met' if ok else '**NOT met**'} ({fn(o[key]):.4g} vs {fn(p[key]):.4g})")
    if "coacd" in by:
        mb, cb = median(o["b"]), median(by["coacd"]["b"])
        out.append(f"- median bytes at most 1/3 of CoACD's: {'met' if mb <= cb / 3 else '**NOT met**'} ({mb:,.0f} vs {cb / 3:,.0f})")
    all_ours = [r for r in records if metrics_of(r, "ours")]
    short = [f"{r['mesh']} ({metrics_of(r, 'ours')['enclosure']:.6f})" for r in all_ours if metrics_of(r, "ours")["enclosure"] < 1.0]
    out.append(
        f"- enclosure 1.0 on every mesh: {'met' if not short else '**NOT met**'} "
        f"({len(all_ours) - len(short)} of {len(all_ours)} evaluated meshes at 1.0"
        + (f"; below: {', '.join(short)}" if short else "")
        + ")"
    )
    return out + [""]


def ours_cells(o):
    """Our N, primitives (kinds), bytes and seconds, or the status."""
    if o.get("primitives") is not None:
        return [str(o["target"]), f"{o['primitives']} ({kinds(o['counts'])})", fmt(o.get("bytes"), ",d"), f"{o['seconds']:.2f}"]
    return ["–", o.get("status", "–"), "–", "–"]


def per_mesh_tables(records, methods):
    peers_ = [m for m in methods if m != "ours"]
    head = "| mesh | faces | ours N | ours primitives | ours bytes | ours s |" + "".join(
        f" {label(m)} primitives | bytes | s |" if m == "ours-rule" else f" {label(m)} hulls | bytes | s |" for m in peers_)
    lines = ["### Size and time", "", head, "|---|---:|---:|---|---:|---:|" + "---:|---:|---:|" * len(peers_)]
    for r in records:
        cells = [r["mesh"], fmt(r.get("faces"), "d")] + ours_cells(r["ours"])
        for m in peers_:
            p = slot(r, m)
            if m == "ours-rule":
                cells += ours_cells(p)[1:]
            elif p.get("status") == "ok" or p.get("hulls"):
                cells += [str(p["hulls"]), fmt(p.get("bytes"), ",d"), f"{p['seconds']:.1f}"]
            else:
                cells += [p.get("status", "–"), "–", "–"]
        lines.append("| " + " | ".join(cells) + " |")
    allm = ["ours"] + peers_
    lines += ["", "### Distance and enclosure", "", "Hausdorff / Chamfer over the diagonal; enclosure = fraction of input samples inside.", ""]
    lines.append("| mesh |" + "".join(f" {label(m)} H | C | E |" for m in allm))
    lines.append("|---|" + "---:|---:|---:|" * len(allm))
    for r in records:
        cells = [r["mesh"]]
        for m in allm:
            x = metrics_of(r, m)
            cells += [f"{x['hausdorff']:.4f}", f"{x['chamfer']:.2e}", f"{x['enclosure']:.4f}"] if x else ["–", "–", "–"]
        lines.append("| " + " | ".join(cells) + " |")
    return lines + [""]


def failures(records, methods):
    lines = ["## Failures, timeouts and meshes not run", ""]
    not_run = {}
    for r in records:
        for m in ["ours"] + [m for m in methods if m != "ours"]:
            s = slot(r, m)
            status = s.get("status", "not run")
            if status == "not run":
                not_run.setdefault(m, []).append(r["mesh"])
            elif status != "ok":
                lines.append(f"- {r['mesh']}, {label(m)}: {status} — {s.get('reason', '')}")
    if len(lines) == 2:
        lines.append("No failure or timeout.")
    for m, meshes in not_run.items():
        lines.append(
            f"- {label(m)} not run on {len(meshes)} meshes (no cached result; `benches/compare` without "
            f"`--cached-only` runs them): {', '.join(meshes)}"
        )
    return lines + [""]


PICS_HEADING = "## Pictures"
# The pictures stand before this section.
PICS_BEFORE = "## Per mesh"


def pictures(records, note=None):
    """A row of thumbnails per mesh (input, ours, CoACD, V-HACD), as the paper's
    figures; `note`, a line under the heading (where the pictures came from)."""
    from . import thumbs

    cols = [c for c in thumbs.COLUMNS if c != "input"]
    lines = [
        f"{PICS_HEADING} (as the paper's figures)",
        "",
        *([note, ""] if note else []),
        f"Each collider drawn over its input mesh by `primdecomp view COLLIDER --input MESH --png OUT "
        f"--png-size {thumbs.SIZE}` (`--compare HULLS.obj` for a peer's hulls): the viewer page's default "
        "three-quarter view, rendered in software. Grey shows the input where it pokes out of a collider. "
        "Colours: box blue, sphere red, capsule green, cylinder orange, frustum purple, prism teal, peer hulls "
        "yellow. The interactive page: `primdecomp view OURS.json --input MESH --compare HULLS.obj -o view.html`.",
        "",
        "| mesh | input | " + " | ".join(label(c) for c in cols) + " |",
        "|---|---|" + "---|" * len(cols),
    ]
    for r in records:
        t = r.get("thumbs") or {}
        if not t:
            continue
        cells = [r["mesh"]]
        for c in ["input"] + cols:
            cells.append(f"![{r['mesh']}, {label(c) if c != 'input' else 'input'}]({thumbs.DIR}/{t[c]})" if c in t else "–")
        lines.append("| " + " | ".join(cells) + " |")
    return lines + [""]


def replace_section(text, heading, lines, before):
    """`text` with the section starting at `heading` (to the next `## ` heading)
    replaced by `lines`, or inserted before the section `before` when absent."""
    body = "\n".join(lines) + "\n"
    at = text.find("\n" + heading)
    if at >= 0:
        end = text.find("\n## ", at + 1)
        return text[: at + 1] + body + (text[end + 1:] if end >= 0 else "")
    at = text.find("\n" + before)
    if at < 0:
        return text.rstrip("\n") + "\n\n" + body
    return text[: at + 1] + body + text[at + 1:]


SIM_HEADING = "## Simulation"


def sim_table(records, note=None):
    """The step-time columns: our median physics step as a ratio to each peer's (wall and
    CPU time), and every collider's similarity to the run on the mesh itself; `note`, a
    line under the heading (where the section came from, when refreshed alone)."""
    rows = [r for r in records if r.get("sim") and r["sim"].get("ours")]
    if not rows:
        return [SIM_HEADING, "", "No simulation results (run `python3 benches/sim_compare.py`, "
                "then regenerate this report).", ""]
    st = next(r["sim"].get("settings", {}) for r in rows)
    g = lambda r, m, k: (r["sim"].get(m) or {}).get(k)  # noqa: E731

    def ratio(r, peer, k, mine="ours"):
        a, b = g(r, mine, k), g(r, peer, k)
        return "–" if a is None or b in (None, 0) else f"{a / b:.2f}"

    def num(x):
        return "–" if x is None else f"{x:.3f}"

    lines = [
        f"{SIM_HEADING} (paper §4.1)",
        "",
        *([note, ""] if note else []),
        f"From `python3 benches/sim_compare.py` (see `docs/results/sim.md`): {st.get('balls', '?')} balls, "
        f"{st.get('frames', '?')} frames, seed {st.get('seed', '?')}, Rapier single-threaded, every collider "
        "of a mesh interleaved frame by frame in one process. Our collider there: the target chosen by the "
        "byte rule above where this report has one from CoACD's bytes, else the same rule against the CoACD hulls "
        "in the peer cache, else max(32, 1% of faces); per mesh in the JSON. Step = median physics-step time per frame (wall clock; CPU time of the "
        "step in brackets); similarity = fraction of balls ending within one diameter of where the same ball "
        "ends on the mesh itself (`src/sim/mod.rs`).",
        "",
        "The last four columns repeat the comparison with ours decomposed to each peer's own hull "
        "count (the same number of colliders in the scene).",
        "",
        "| mesh | our prims | ours/CoACD step | ours/V-HACD step | similarity ours | CoACD | V-HACD "
        "| at CoACD's count: step ratio | similarity | at V-HACD's count: step ratio | similarity |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        cells = [r["mesh"], str(r["sim"].get("settings", {}).get("ours_primitives", "–"))]
        for peer in ("coacd", "vhacd"):
            cells.append(f"{ratio(r, peer, 'frame_ms_median')} ({ratio(r, peer, 'cpu_ms_median')})")
        cells += [num(g(r, m, "similarity")) for m in ("ours", "coacd", "vhacd")]
        for peer in ("coacd", "vhacd"):
            at = f"ours_at_{peer}"
            cells.append(f"{ratio(r, peer, 'frame_ms_median', at)} ({ratio(r, peer, 'cpu_ms_median', at)})")
            cells.append(num(g(r, at, "similarity")))
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    for peer, label in (("coacd", "CoACD"), ("vhacd", "V-HACD")):
        for mine, how in (("ours", "at the byte rule"), (f"ours_at_{peer}", f"at {label}'s hull count")):
            both = [r for r in rows if g(r, peer, "frame_ms_median") is not None
                    and g(r, mine, "frame_ms_median") is not None]
            if not both:
                continue
            fast = sum(g(r, mine, "frame_ms_median") <= g(r, peer, "frame_ms_median") for r in both)
            cpu = sum(g(r, mine, "cpu_ms_median") <= g(r, peer, "cpu_ms_median") for r in both)
            sim = sum(g(r, mine, "similarity") >= g(r, peer, "similarity") for r in both)
            ok = "met" if fast == len(both) and sim == len(both) else "**NOT met**"
            # Beyond noise: slower by more than the mesh's own spread (sim_compare.py).
            timed = [r for r in both if g(r, "self", "frame_ms_median") and g(r, "mesh", "frame_ms_median")]
            spread = lambda r: step_spread(g(r, "self", "frame_ms_median"), g(r, "mesh", "frame_ms_median"))  # noqa: E731
            slower = sum(g(r, mine, "frame_ms_median") / g(r, peer, "frame_ms_median") - 1 > spread(r) for r in timed)
            noise = f", slower beyond the mesh's own spread on {slower} of {len(timed)}" if timed else ""
            lines.append(f"- Goal (frame time ≤ {label}'s and similarity ≥ {label}'s on every mesh), ours {how}: "
                         f"{ok} — step ≤ on {fast} of {len(both)} meshes by wall clock, {cpu} by CPU time{noise}; "
                         f"similarity ≥ on {sim} of {len(both)}.")
    return lines + [""]


def render(records, methods, a, cmd, commit, seconds):
    if getattr(a, "ours_mode", "level") == "cut":
        return render_cut(records, methods, a, cmd, commit, seconds)
    main3 = ["ours"] + [m for m in ("coacd", "vhacd") if m in methods]
    _, rows, table = summary_table(records, main3)
    text = [
        "# primdecomp vs CoACD and V-HACD",
        "",
        f"Generated by `{cmd}` at commit `{commit}` on {datetime.date.today()} ({machine()}), "
        f"in {seconds / 60:.1f} min. Regenerate with the same command (peer results are cached in "
        "`benches/.cache` by mesh sha256 + settings; `--cached-only` never starts a peer).",
        "",
        f"- Rule: {RULE}.",
        "- Our engine: the release binary, default settings, `--threads 1`; seconds are the whole multi-target "
        "pass (load to post-processing), so a single-target run is faster.",
        peers_line(a),
        metrics_line(a),
        "",
        "## Summary (as the paper's Table 3)",
        "",
        *table,
        "",
    ]
    if "coacd-paper" in methods:
        common2, _, t2 = summary_table(records, ["ours", "coacd-paper"])
        text += ["Against CoACD with the paper author's settings:", ""]
        text += [*t2, ""] if common2 else ["No mesh has a CoACD (paper settings) result yet.", ""]
    text += targets_check(records, rows, main3)
    text += plot_links("compare")
    text += pictures(records)
    text += ["## Per mesh (as the paper's appendix)", "", "Primitive letters: b box, s sphere, c capsule, y cylinder, f frustum, p prism.", ""]
    text += per_mesh_tables(records, ["ours"] + methods)
    text += failures(records, methods)
    text += sim_table(records)
    return "\n".join(text)


def peers_line(a):
    return (f"- Peers (versions pinned in `benches/peers/requirements.txt`), one thread each (OMP_NUM_THREADS={a.threads}), "
            f"timeout {a.timeout:.0f} s per run: CoACD with defaults; CoACD with the paper author's settings (threshold 0.08, "
            "resolution 5000, preprocess_resolution 50, decimate on, merge off); V-HACD 4 (vhacdx) with defaults. "
            "Seconds are the decomposition call's wall time.")


def metrics_line(a):
    return (f"- Metrics: `primdecomp eval` with {a.samples or 'its default'} samples per surface (see "
            "`primdecomp eval --help` for definitions and sampling error). Bytes by the paper's Table 2.")


def plot_links(name):
    return ["## Plots", "", f"![distance per mesh]({name}_distance.png)", "", f"![bytes per mesh]({name}_bytes.png)", "",
            f"![seconds vs faces]({name}_seconds.png)", ""]


PEER_SETTINGS = {
    "coacd": "CoACD with defaults",
    "coacd-paper": "CoACD with the paper author's settings (threshold 0.08, resolution 5000, preprocess_resolution 50, "
                   "decimate on, merge off)",
    "vhacd": "V-HACD 4 (vhacdx) with defaults",
}


def render_cut(records, methods, a, cmd, commit, seconds):
    """The `--ours-mode cut` report: our merge-tree cut at a third of CoACD's bytes,
    the byte rule's level beside it, no pictures and no simulation section."""
    peers_ = [m for m in ("coacd", "vhacd") if m in methods]
    common, rows, table = summary_table(records, ["ours", "ours-rule"] + peers_)
    note = getattr(a, "note", "")
    text = [
        "# primdecomp's merge-tree cut vs CoACD and V-HACD",
        "",
        f"Generated by `{cmd}` at commit `{commit}` on {datetime.date.today()} ({machine()}), "
        f"in {seconds / 60:.1f} min. `docs/results/compare.md` is the default report (`--ours-mode level`).",
        "",
        *([note, ""] if note else []),
        f"Meshes in the summary ({len(common)}, every method with results): {', '.join(r['mesh'] for r in common) or 'none'}.",
        "",
        f"- Rule: {CUT_RULE}.",
        f"- Our engine: the release binary `{a.bin}`, default settings otherwise, `--threads 1`; our seconds are the "
        "one `--max-bytes` run (load to post-processing, its cut and distance stages included); the byte rule's "
        "seconds are its whole multi-target pass.",
        f"- Peers (versions pinned in `benches/peers/requirements.txt`), one thread each (OMP_NUM_THREADS={a.threads}), "
        f"timeout {a.timeout:.0f} s per run: " + "; ".join(PEER_SETTINGS[m] for m in methods) + ". Seconds are the "
        "decomposition call's wall time.",
        metrics_line(a),
        "",
        "## Summary (as the paper's Table 3)",
        "",
        *table,
        "",
    ]
    text += targets_check(records, [r for r in rows if r["method"] != "ours-rule"], ["ours"] + peers_)
    text += plot_links(getattr(a, "report_name", "compare_cut"))
    text += ["## Per mesh (as the paper's appendix)", "", "Primitive letters: b box, s sphere, c capsule, y cylinder, f frustum, p prism. "
             "ours N: the -n cap.", ""]
    text += per_mesh_tables(records, ["ours", "ours-rule"] + methods)
    text += failures(records, ["ours-rule"] + methods)
    return "\n".join(text)
