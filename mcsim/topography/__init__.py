"""Measured surfaces: AFM readers, levelling and summit identification, measured height distributions."""
