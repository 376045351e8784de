"""The native hold's hand-over (exuclear.engine.impulse_hold): a multiplier whose ring grows
window after window is handed to the velocity-level condition; one that rocks on its wall as
much without growing, or that surges smoothly, stays held.  Multiplier sequences fed to
:meth:`DistanceHold._rings_up`, whose rings are known in closed form."""
import math
from types import SimpleNamespace

from exuclear.engine import impulse_hold
from exuclear.engine.impulse_hold import HAND_OVER, RING_STEPS, RING_WINDOWS, DistanceHold

REACTION = 100.0  # N, the load the multiplier rings about


def first_hand_over(forces):
    """The index of the first multiplier at which the hold hands over (None: never)."""
    hold = SimpleNamespace(_forces=[], _window=impulse_hold._NO_RING)
    for n, force in enumerate(forces):
        if DistanceHold._rings_up(hold, force, REACTION):
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
