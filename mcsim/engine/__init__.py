"""The Monte Carlo engine: compiled kernels, sampling and summation, one pad's own curves
(``pads/``), whole design maps at once (``maps/``), the GPU backend, Dask clusters,
interrupts, estimates from sums."""
