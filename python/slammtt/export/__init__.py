"""slammtt-export: a log of the stack into the formats other tools read (docs/export.md):
TUM trajectories (evo), CSV tables, MOTChallenge tracks and truth (py-motmetrics, TrackEval),
MCAP with Foxglove schemas (slammtt.foxglove.convert, shared with the live view)."""
