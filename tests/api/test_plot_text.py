"""Every text of a saved figure reads as written: names stay literal (a `$` in a pulley name is not
math text) and a log axis's tick labels are plain numbers (they printed as raw
`$\\mathdefault{10^{-1}}$`, cut off, on every spectrum plot)."""
from drivedyn.core.plotting import figure, savefig


def test_log_axis_ticks_are_plain_and_names_literal(tmp_path):
    fig, axes = figure()
    ax = axes[0, 0]
    ax.semilogy([1, 2, 3], [1e-3, 1e-1, 10], label="pulley $x")
    ax.legend()
    savefig(fig, tmp_path / "f.png")
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert labels and all("$" not in s and "mathdefault" not in s for s in labels), labels
    assert ax.get_legend().get_texts()[0].get_text() == "pulley $x"
