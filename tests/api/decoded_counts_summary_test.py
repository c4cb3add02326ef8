"""``DecodedCounts`` prints a one-line summary (shots, outcomes, feasible share, best cost, P(optimum)), not its
outcomes; ``to_dict`` keeps every outcome."""

from __future__ import annotations

import qcpp


def test_the_printed_summary_names_the_shots_and_shares_not_each_outcome() -> None:
    s = qcpp.grid_scenario(2, 3, robots=1)
    n = s.num_variables
    counts = {format(k, f"0{n}b"): 1 + k % 5 for k in range(1 << n)}  # every outcome, a few feasible
    d = qcpp.decode_counts(s, counts, optimum=qcpp.solve(s))
    text = repr(d)
    assert text == str(d) and "\n" not in text and len(text) < 150
    assert text == (
        f"DecodedCounts(shots={d.shots}, outcomes={1 << n}, feasible_share={d.feasible_share:.4g}, "
        f"best_cost={d.best_cost:.6g}, p_optimum={d.p_optimum:.4g})"
    )
    assert "Outcome(" not in text and len(d.to_dict()["outcomes"]) == 1 << n
    assert 0 < d.feasible_share < 1 and d.p_optimum


def test_the_summary_says_none_where_nothing_was_feasible_or_no_optimum_was_given() -> None:
    s = qcpp.grid_scenario(2, 2, robots=1)
    assert repr(qcpp.decode_counts(s, {"1111": 4})) == (
        "DecodedCounts(shots=4, outcomes=1, feasible_share=0, best_cost=None, p_optimum=None)"
    )
