"""The physics as pure functions: per-summit contact laws, the GW integrals and analytic curves, adhesion summaries, mean-field load control.

See docs/physics.md, section 'Units and conventions' (and the sections it lists).
"""
