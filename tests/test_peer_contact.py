"""exuclear's joint and Exudyn's ObjectContactSphereSphere on the paper's journal impact
(validation/peer_contact.py): the same departure velocity under each solver of the benchmark."""
from __future__ import annotations

import pytest

from validation import peer_contact as pc


@pytest.mark.parametrize("name, settings", pc.SOLVERS, ids=[name for name, _ in pc.SOLVERS])
def test_both_elements_give_the_papers_departure_velocity(name, settings):
    # X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597, section 5.1:
    # departure 0.269 m/s after an impact at 0.3 m/s with cr = 0.9 (its Wang-Liu law).  Both
    # elements run the Hertz law with the exact Carvalho-Martins restitution, 0.9 x 0.3 =
    # 0.270 m/s, 0.4 % above the paper's; 1 % is the tolerance the project's issue set for the paper's numbers.
    ours, peer = pc.solve(pc.build_ours, settings), pc.solve(pc.build_peer, settings)
    assert ours.ok, ours.message
    assert peer.ok, peer.message
    assert ours.departure == pytest.approx(pc.PAPER_DEPARTURE, rel=0.01)
    assert peer.departure == pytest.approx(pc.PAPER_DEPARTURE, rel=0.01)
    # the same law on the same steps: the two agree far closer than to the paper (measured: within
    # 5e-6 relative); 1e-4 leaves room for DOPRI5's own step sequences (80 and 81 steps) and catches
    # a peer whose contact stays off for the first step (PEER_START_GAP = 0: 1.5e-4 off under RK44)
    assert ours.departure == pytest.approx(peer.departure, rel=1e-4)
