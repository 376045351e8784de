"""The native hold's hand-over (exuclear.engine.impulse_hold): a multiplier whose ring grows
window after window, or rings beyond the share at a step Exudyn shortened, is handed to the
velocity-level condition; one that rocks on its wall as much without growing, or that
surges smoothly, stays held.  Multiplier sequences fed to :meth:`DistanceHold._rings_up`,
whose rings are known in closed form."""
import math
from types import SimpleNamespace

from exuclear.engine import impulse_hold
from exuclear.engine.impulse_hold import HAND_OVER, RING_STEPS, RING_WINDOWS, DistanceHold

REACTION = 100.0  # N, the load the multiplier rings about
STEP = 1e-3  # s, the held steps' length


def first_hand_over(forces, steps=None):
    """The index of the first multiplier at which the hold hands over (None: never); the
    steps' lengths ``steps`` [s] (default: all STEP)."""
    hold = SimpleNamespace(_forces=[], _window=impulse_hold._NO_RING, _step=math.inf)
    for n, force in enumerate(forces):
        if DistanceHold._rings_up(hold, force, REACTION, STEP if steps is None else steps[n]):
            return n
    return None


def test_a_ring_that_grows_window_after_window_is_handed_over_once_beyond_the_share():
    # an oscillation of 4 steps a period, f_n = R + A_n cos(n pi / 2): its second difference
    # is 2 A_n with its sign changing every step, a ring of A_n / 2.  Its amplitude grows by
    # 1.2 % a step (1.46 a window, the 3D four-bar's ring): it is handed over once its ring is
    # beyond HAND_OVER of R, A_n > 2 HAND_OVER R, after RING_WINDOWS windows of growth, at
    # the first step of a window whose ring has grown past RING_GROWTH times the window
    # before's (within the window: 1.012^32 = 1.46 > RING_GROWTH)
    growth, start = 1.012, 1.0
    forces = [REACTION + start * growth**n * math.cos(0.5 * math.pi * n) for n in range(2000)]
    n = first_hand_over(forces)
    beyond = math.log(2.0 * HAND_OVER * REACTION / start) / math.log(growth)  # the step A_n reaches it
    assert n is not None and beyond <= n < beyond + RING_STEPS
    assert n >= RING_WINDOWS * RING_STEPS


def test_a_journal_rocking_on_its_wall_and_a_smooth_surge_stay_held():
    # rocking: 6 steps a period at 0.9 of the load, its ring 0.9 R / 4 at most (the second
    # difference of a cosine of 6 steps a period has its amplitude), not growing; a surge:
    # the load rising tenfold and back over 80 steps, its second difference keeping its sign
    # over each flank (the ring counts only where it changes)
    rocking = [REACTION * (1.0 + 0.9 * math.cos(math.pi * n / 3.0)) for n in range(2000)]
    assert first_hand_over(rocking) is None
    surge = [REACTION * (1.0 + 9.0 * math.exp(-(((n % 400) - 200) / 20.0) ** 2)) for n in range(2000)]
    assert first_hand_over(surge) is None


def test_a_ring_beyond_the_share_is_handed_over_where_exudyn_shortens_the_step():
    # an alternation of 0.3 R, f_n = R (1 + 0.3 (-1)^n): its ring 0.3 R, beyond HAND_OVER
    # of R but not growing, stays held at a steady step; where Exudyn halves the step (after
    # a failed Newton, which the ring's 4 m v / h doubles at each halving) it is handed over
    # at the shortened step
    forces = [REACTION * (1.0 + 0.3 * (-1) ** n) for n in range(1000)]
    assert first_hand_over(forces) is None
    steps = [STEP if n < 600 else 0.5 * STEP for n in range(1000)]
    assert first_hand_over(forces, steps) == 600
    # below the share, a halving leaves the hold on
    calm = [REACTION * (1.0 + 0.2 * (-1) ** n) for n in range(1000)]
    assert first_hand_over(calm, steps) is None
