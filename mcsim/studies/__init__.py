"""What users run: one simulation, sweeps over inputs, pad statistics, the paper's reproduction, AFM ingestion."""
