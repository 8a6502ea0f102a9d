"""The Monte Carlo engine: compiled kernels, sampling and summation, the GPU backend, Dask clusters, interrupts, estimates from sums."""
