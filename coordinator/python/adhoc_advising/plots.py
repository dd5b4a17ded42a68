"""The reports' figures drawn with matplotlib from :func:`adhoc_advising.load`'s
DataFrames, so they can be restyled (``pip install matplotlib``).

    >>> from adhoc_advising import load, plots
    >>> study = load("out/quick")
    >>> plots.curves(study, "goal_pct")          # goal_pct.svg of REPORT.md
    >>> plots.gain_vs_messages(study)            # gain_vs_messages.svg
    >>> plots.frontier(study, cost="bytes")      # frontier_bytes.svg

Each function draws on ``ax`` (a new figure's when ``None``) and returns it.
They read only the summaries and ``significance.json``, which the
reproductions under docs/reproduction/ carry.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from adhoc_advising.results import Experiment, Study

if TYPE_CHECKING:
    from matplotlib.axes import Axes

#: What each metric's axis says, as the reports' figures say it.
LABELS = {
    "goal_pct": "goal %",
    "time_to_goal": "frames to goal",
    "spent_budget": "budget spent",
    "advising_messages": "advising messages per training episode",
    "advising_bytes": "advising bytes per training episode",
}


def _axes(ax: Axes | None) -> Axes:
    if ax is not None:
        return ax
    try:
        import matplotlib.pyplot as plt
    except ImportError as error:  # pragma: no cover - depends on the environment
        message = "adhoc_advising.plots needs matplotlib: pip install matplotlib"
        raise ImportError(message) from error
    return plt.subplots(figsize=(7, 4.5))[1]


def curves(
    results: Study | Experiment,
    metric: str = "goal_pct",
    ax: Axes | None = None,
    last: int | None = None,
) -> Axes:
    """Each entry's mean ``metric`` at every evaluation with its interval as
    a band, from the summaries; ``last``: only the last so many training
    episodes (the reports' ``goal_pct_last`` zooms on the last 20%)."""
    ax = _axes(ax)
    summary = results.summary
    groups: Any = summary.groupby("entry", sort=False) if "entry" in summary else [("", summary)]
    for name, points in groups:
        if last is not None:
            points = points[points.episode >= points.episode.max() - last]
        line = ax.plot(points.episode, points[metric], label=name or None)[0]
        ax.fill_between(
            points.episode,
            points[f"{metric}_ci_low"],
            points[f"{metric}_ci_high"],
            color=line.get_color(),
            alpha=0.2,
            linewidth=0,
        )
    ax.set_xlabel("training episodes")
    ax.set_ylabel(LABELS.get(metric, metric))
    if "entry" in summary:
        ax.legend()
    return ax


def gains(study: Study, window: str = "last_ten_gain", ax: Axes | None = None) -> Axes:
    """Each entry's gain over its baseline (``last_ten_gain`` or
    ``area_gain``) with its paired interval, from ``significance.json``."""
    ax = _axes(ax)
    g = study.gains.iloc[::-1]
    gain = g[window].to_numpy()
    errors = [gain - g[f"{window}_ci_low"].to_numpy(), g[f"{window}_ci_high"].to_numpy() - gain]
    ax.errorbar(gain, g.entry.to_numpy(), xerr=errors, fmt="o", capsize=3)
    ax.axvline(0, color="grey", linewidth=0.8)
    baselines = study.gains.baseline.unique() if len(study.gains) else []
    baseline = baselines[0] if len(baselines) == 1 else "its baseline"
    ax.set_xlabel(f"goal % gain over {baseline}")
    return ax


def gain_vs_messages(study: Study, ax: Axes | None = None) -> Axes:
    """Each method's last-ten gain (whisker: its interval) against the
    advising messages each agent sent per training episode, over the whole
    training (``gain_vs_messages.svg``)."""
    ax = _axes(ax)
    team_size = {name: len(e.config["config"]["team"]) for name, e in study.entries.items()}
    s = study.summary.dropna(subset=["advising_messages"])
    s = s.assign(episodes=s.groupby("entry").episode.diff().fillna(s.episode))
    s = s.assign(sent=s.advising_messages * s.episodes)
    sent = s.groupby("entry").sent.sum() / s.groupby("entry").episodes.sum()
    for _, g in study.gains.iterrows():
        x = sent[g.entry] / team_size[g.entry]
        y = g.last_ten_gain
        ax.errorbar(
            [x],
            [y],
            yerr=[[y - g.last_ten_gain_ci_low], [g.last_ten_gain_ci_high - y]],
            fmt="o",
            capsize=3,
        )
        ax.annotate(g.entry, (x, y), xytext=(5, 3), textcoords="offset points")
    ax.axhline(0, color="grey", linewidth=0.8)
    ax.set_xlabel("advising messages per agent per training episode")
    ax.set_ylabel("goal % gain, last ten evaluations")
    return ax


def frontier(study: Study, cost: str = "messages", ax: Axes | None = None) -> Axes:
    """The communication frontier (``frontier_messages.svg``,
    ``frontier_bytes.svg``): each entry's last-ten gain over the baseline
    against the advising ``cost`` (``"messages"`` or ``"bytes"``) each agent
    sent per training episode, on a log axis, with both intervals as
    whiskers; one colour per group, its entries joined in order of cost, the
    Pareto front ringed. Entries that sent nothing have no place on a log
    axis: the legend counts them beside their group. From
    ``significance.json``'s ``frontier`` (:attr:`Study.frontier`)."""
    if cost not in ("messages", "bytes"):
        raise ValueError(f'cost must be "messages" or "bytes", got {cost!r}')
    if study.frontier.empty:
        raise ValueError(
            f"{study.path} has no frontier in significance.json: it needs a baseline and "
            "two or more entries compared with it (an older study's comes from `analyse DIR`)"
        )
    ax = _axes(ax)
    for group, points in study.frontier.groupby("group", sort=False):
        placed = points[(points[cost] > 0) & points.last_ten_gain.notna()].sort_values(cost)
        silent = int((points[cost] == 0).sum())
        if not silent:
            label = group
        elif placed.empty:
            label = f"{group} (sent none)"
        else:
            label = f"{group} ({silent} sent none)"
        x, y = placed[cost].to_numpy(), placed.last_ten_gain.to_numpy()
        xerr = [x - placed[f"{cost}_ci_low"].to_numpy(), placed[f"{cost}_ci_high"].to_numpy() - x]
        yerr = [
            y - placed.last_ten_gain_ci_low.to_numpy(),
            placed.last_ten_gain_ci_high.to_numpy() - y,
        ]
        ax.errorbar(x, y, xerr=xerr, yerr=yerr, fmt="-o", capsize=3, label=label)
        front = placed[placed[f"front_{cost}"]]
        ax.scatter(
            front[cost],
            front.last_ten_gain,
            s=160,
            facecolors="none",
            edgecolors="black",
            linewidths=1.5,
            zorder=3,
        )
    ax.set_xscale("log")
    ax.axhline(0, color="grey", linewidth=0.8)
    ax.set_xlabel(f"advising {cost} per agent per training episode")
    ax.set_ylabel("goal % gain, last ten evaluations")
    ax.legend()
    return ax
