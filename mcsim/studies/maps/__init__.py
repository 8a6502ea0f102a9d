"""Studies of a measured height map: read once (:mod:`mcsim.topography.maps`), then ingested
into a GW surface (``ingest``, its result ``ingested``), pressed exactly beside GW
(``contact``) with GW's radius calibrated on it (``calibration``), its exact adhesive cycle
beside GW's adhesion (``adhesivecontact``) with GW's adhesion calibrated (``adhesioncalibration``),
and pads synthesised from its spectrum (``synthpads``)."""
