"""Whole analytic design maps at once: the compiled jkr path (``designmap``), its kernel as
plain numba functions, dry (``kernel``, with its on-disk cache stamped by code) and with an
environment (``environment``), and a point's status codes (``status``)."""
