"""Status of a design map's point, set by its kernels (:mod:`mcsim.engine.maps.kernel`,
:mod:`mcsim.engine.maps.environment`) and read by :mod:`mcsim.engine.maps.designmap` and the sweeps.

* :data:`OK`: summarised by the kernel;
* :data:`NO_REST`: the approach load is never tensile: the surfaces rest apart (zero pull-off,
  work and hysteresis);
* :data:`REFERENCE`: outside the fast path (the approach load stays tensile down to
  h = -1e6): the reference path, :func:`mcsim.physics.adhesion.adhesion_summary`, reports it.
"""

OK, NO_REST, REFERENCE = 0, 1, 2
