"""One pad from its summits drawn again: its net load and where its curve is smooth (``load``),
its force-controlled turn, exact pull-off and work of separation (``curves``), in humid air the
turn and pull-off by branch and bound on per-summit bounds (``bounds``; its bookkeeping
compiled, ``gaps``), its static friction at its turn and the normal load of its μ_s
(``friction``)."""
