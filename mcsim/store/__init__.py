"""Files: run files and checkpoints, run results, sweep files, TOML configurations, safe writing of every output."""
