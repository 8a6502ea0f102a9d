"""The inputs and their quantities: units, surfaces and materials, presets, height distributions, errors."""
