"""How a device is routed: one frozen value with every setting of routing, allocation, placement and their searches.

:class:`RoutingOptions` is created once per compile or estimate (:data:`DEFAULT_ROUTING` unless the caller asks for
another) and passed down explicitly to every router and search: no module constant is read at run time, so two
runs with equal options route alike, and memos (:class:`qcpp.routing.context.RoutingContext`) key on the options
value itself. The defaults are the measured settings (``docs/resource-estimates.md``, ``benchmarks/routing.py``).

Example:
    >>> from dataclasses import replace
    >>> DEFAULT_ROUTING.trials, DEFAULT_ROUTING.window_radius
    (16, 2)
    >>> cells = DEFAULT_ROUTING.for_cells()
    >>> cells.large_window_seeds, cells.large_window_trials
    (32, 64)
    >>> replace(DEFAULT_ROUTING, trials=4) == DEFAULT_ROUTING
    False
"""

from __future__ import annotations

from dataclasses import dataclass, replace

__all__ = [
    "DEFAULT_ROUTING", "DEFAULT_TRIALS", "EFFORTS", "QUICK_ROUTING", "RoutingOptions", "effort_of", "effort_routing",
]

DEFAULT_TRIALS = 16
"""SABRE trials per routing: the best of 16 randomised routings (Qiskit's default is the CPU count, which would make
the routing depend on the machine)."""


@dataclass(frozen=True)
class RoutingOptions:
    """Every setting of routing onto a device (hashable: memo keys use it).

    Attributes:
        trials: SABRE's trials per routing (``None``: Qiskit's default).
        window_radius: A window is routed on the device qubits within this many couplings of its qubits' positions
            (more if that patch is not connected): its routed cost then depends only on its neighbourhood.
        window_seeds: SABRE seeds tried per part of a window (the fewest SWAPs wins).
        large_window_pairs: Windows whose compute has at least this many two-qubit gates (the balance arithmetic's
            one window; a hard obstacle or a small grid leaves it 100-200 compute gates) try
            :attr:`large_window_seeds` seeds (and, up to :attr:`large_window_max_pairs`, also
            :attr:`wide_window_seeds` seeds of :attr:`wide_window_trials` trials); the try whose whole window
            (compute, register phase, uncompute) routes to the fewest CX wins, the first on ties: SABRE picks the
            fewest SWAPs for the compute alone, but where the compute leaves the register bits decides what the
            phase between them costs.
        large_window_seeds: Seeds tried per large window.
        large_window_trials: SABRE's trials per seed on a large window (``None``: :attr:`trials`).
        wide_window_seeds: Seeds of the wider search, tried after the :attr:`large_window_seeds` ones; the tries
            include the narrower search's, so a window never routes to more CX than without it.
        wide_window_trials: SABRE's trials per routing of the wider search (at least :attr:`trials`).
        large_window_max_pairs: Windows whose compute has more two-qubit gates than this get no wider search (its
            time grows with the window's size).
        commuting_phases: A window whose middle is a run of commuting blocks (the balance arithmetic's register
            phase, an Ising phase: :func:`qcpp.routing.commuting.commuting_blocks`) also routes that middle in any
            order (:func:`qcpp.routing.commuting.route_blocks`); per try, whichever middle gives the whole window
            fewer CX is kept, SABRE's on ties, so a window never routes to more CX than without it.
        cell_large_window_seeds: :attr:`large_window_seeds` on the heavy-hex cells (:meth:`for_cells`).
        cell_large_window_trials: :attr:`large_window_trials` on the heavy-hex cells.
        cell_screen: The heavy-hex cells' plan choice (:func:`qcpp.pipeline.cellmixer.cell_mixers`) runs the
            allocation search on the default plan and on this many variants, those whose windows route to the
            fewest two-qubit gates with the greedy allocation (``0``: on every variant).
        cell_swap_screen: The cells' plan choice searches an exchange of operands only if, with its ancillas on
            the sites the search found for the plan it is tried against, it routes to no more CX than that plan
            there (an exchange changes which qubits one AND or the rotation brings together, not where the
            ancillas go); ``False``: every exchange is searched. The chosen plan still never routes to more than
            the default plan.
        route_ahead: Whether a compile on the geometric layouts routes its large windows in a forked process
            while the heavy-hex cells' plans are chosen and the ancillas allocated (:mod:`qcpp.routing.prefetch`;
            on Linux with two usable cores): the same circuit either way, sooner.
        allocation_search: Whether the medial allocation searches the partial mixers' ancilla sites
            (:func:`qcpp.layout.medial.allocate_ancillas` ``search``).
        search_ranks: Each ancilla of a searched section is also tried on its 2nd .. (1 + this)-th best free qubit.
        search_rounds: Rounds of the allocation search (each tries every ancilla on each of its ranks).
        search_max_pairs: Sections with more two-qubit gates keep the greedy allocation.
        search_margin: Device rows and columns around a section's data that its search result depends on (its
            ancillas land within two steps of their partners, its window routes within two steps of them).
        placement_max_twoq: The greedy path searches placements on circuits of at most this many two-qubit gates
            (:func:`qcpp.layout.placement_search.search_route`); larger circuits keep one routing.
        placement_layouts: ``SabreLayout`` starts per placement search.
        placement_seeds: SABRE routing seeds per layout of the placement search (the first for every layout, all
            for the :attr:`placement_refine` cheapest).
        placement_refine: Layouts of the placement search routed with every seed.
        sabre_layout_trials: Random starts per ``SabreLayout`` run (explicit: Qiskit's default is the CPU count).
        calibrated_routings: On a named (calibrated) device, compile's own routings the candidates start from: the
            placement search's cheapest few (:func:`qcpp.pipeline.device_compile.greedy_routes`), each then
            optimised and placed by the errors (:mod:`qcpp.pipeline.candidates`).
        calibrated_placement_layouts: :attr:`placement_layouts` on a named device (:meth:`for_calibrated`): there
            a routing is judged by its success probability, and a wider search finds routings whose few extra
            SWAPs, or whose shape, sit on better qubits.
        calibrated_placement_refine: :attr:`placement_refine` on a named device.
        mixer_variant_layouts: On a circuit routed whole, each partial mixer's equally cheap plans are scored by
            a shorter placement search of this many ``SabreLayout`` starts (:mod:`qcpp.pipeline.routed_mixers`;
            ``0``: the plan's own networks are kept).
        mixer_variant_seeds: Routing seeds per layout of that search.
        mixer_variant_budget: That choice stops once the circuits it has routed hold this many two-qubit gates in
            all (each scoring routes the whole circuit; compile time grows with the circuit's size and depth).
        lattice_search_max_distance: On a named heavy-hex device, a circuit the placement search routes whole is
            also compiled the same way (greedy layout, placement search, partial mixers planned for the routing) on
            every defect-free ``heavy-hex:D`` lattice that holds it up to this distance, and those routings are
            placed on the device where their couplers embed (:func:`qcpp.pipeline.device_compile.compile_for_device`;
            ``0``: none). A lattice of another size and shape starts SABRE elsewhere, and no one size wins.
        auto_compare_max_twoq: Below this many lowered two-qubit gates the ``auto`` layout also tries ``greedy``
            on the geometric layout's device (one routing of a tiny circuit may need fewer SWAPs than windows).
        greedy_compare_max_qubits: ``auto`` routes its greedy comparison on the medial grid itself up to this many
            qubits, on its top-left sub-grid holding the circuit's qubits beyond (a dense distance matrix of every
            device qubit is costly).
        crop_min_qubits: Square grids of more qubits whose medial layout leaves rows or columns far from every home
            are routed on the part around the layout.
        crop_pad: Free rows and columns such a crop keeps beyond the homes' bounding box (more than an ancilla, a
            relay holder or a routing patch reaches).
    """

    trials: int | None = DEFAULT_TRIALS
    window_radius: int = 2
    window_seeds: int = 1
    large_window_pairs: int = 100
    large_window_seeds: int = 8
    large_window_trials: int | None = None
    wide_window_seeds: int = 16
    wide_window_trials: int = 128
    large_window_max_pairs: int = 1_000
    commuting_phases: bool = True
    cell_large_window_seeds: int = 32
    cell_large_window_trials: int = 64
    cell_screen: int = 4
    cell_swap_screen: bool = True
    route_ahead: bool = True
    allocation_search: bool = True
    search_ranks: int = 4
    search_rounds: int = 2
    search_max_pairs: int = 200
    search_margin: int = 2
    placement_max_twoq: int = 400
    placement_layouts: int = 24
    placement_seeds: int = 4
    placement_refine: int = 6
    sabre_layout_trials: int = 1
    calibrated_routings: int = 12
    mixer_variant_seeds: int = 2
    mixer_variant_budget: int = 8_000
    mixer_variant_layouts: int = 8
    lattice_search_max_distance: int = 9
    calibrated_placement_layouts: int = 96
    calibrated_placement_refine: int = 12
    auto_compare_max_twoq: int = 2_000
    greedy_compare_max_qubits: int = 1_024
    crop_min_qubits: int = 1_024
    crop_pad: int = 6

    @property
    def window_key(self) -> tuple[int | None, ...]:
        """The settings a window's routing depends on (:func:`qcpp.routing.windows.route_window`: SABRE's trials,
        the patch radius, the seeds and the large windows' searches), so options that differ only in the
        allocation or placement searches share routed windows in a memo.

        >>> from dataclasses import replace
        >>> replace(DEFAULT_ROUTING, search_ranks=1).window_key == DEFAULT_ROUTING.window_key
        True
        """
        return (self.trials, self.window_radius, self.window_seeds, self.large_window_pairs, self.large_window_seeds,
                self.large_window_trials, self.wide_window_seeds, self.wide_window_trials,
                self.large_window_max_pairs)  # fmt: skip

    def for_cells(self) -> RoutingOptions:
        """These options with the heavy-hex cells' large-window search (:attr:`cell_large_window_seeds` seeds of
        :attr:`cell_large_window_trials` trials)."""
        return replace(self, large_window_seeds=self.cell_large_window_seeds,
                       large_window_trials=self.cell_large_window_trials)  # fmt: skip

    def for_calibrated(self) -> RoutingOptions:
        """These options with a named device's placement search (:attr:`calibrated_placement_layouts` starts, the
        :attr:`calibrated_placement_refine` cheapest routed with every seed).

        >>> DEFAULT_ROUTING.for_calibrated().placement_layouts, DEFAULT_ROUTING.placement_layouts
        (96, 24)
        """
        return replace(self, placement_layouts=self.calibrated_placement_layouts,
                       placement_refine=self.calibrated_placement_refine)  # fmt: skip


DEFAULT_ROUTING = RoutingOptions()
"""The measured settings: what ``qcpp compile --device`` and ``qcpp estimate --device`` route with."""

QUICK_ROUTING = replace(DEFAULT_ROUTING, mixer_variant_layouts=0)
"""``qcpp compile --effort quick``: the measured settings without the partial mixers' choice for the routing
(:mod:`qcpp.pipeline.routed_mixers`), which is most of a compile on a named device (it runs on every host the
placement searches use); every other search stays. ``benchmarks/compile_effort.py`` prints what it costs and
saves on the calibrated devices."""

EFFORTS = ("full", "quick")
"""The compile efforts, most thorough first: ``full`` is :data:`DEFAULT_ROUTING`, ``quick`` :data:`QUICK_ROUTING`."""


def effort_routing(effort: str) -> RoutingOptions:
    """The routing settings of a compile effort (:data:`EFFORTS`).

    Raises:
        ValueError: an effort not in :data:`EFFORTS`.

    >>> effort_routing("full") == DEFAULT_ROUTING, effort_routing("quick").mixer_variant_layouts
    (True, 0)
    """
    if effort == "full":
        return DEFAULT_ROUTING
    if effort == "quick":
        return QUICK_ROUTING
    raise ValueError(f"effort must be one of {', '.join(EFFORTS)}, not {effort!r}")


def effort_of(routing: RoutingOptions) -> str:
    """The name of ``routing`` among :data:`EFFORTS`, or ``custom`` (settings no effort names).

    >>> effort_of(QUICK_ROUTING), effort_of(replace(DEFAULT_ROUTING, trials=4))
    ('quick', 'custom')
    """
    return next((name for name in EFFORTS if effort_routing(name) == routing), "custom")
