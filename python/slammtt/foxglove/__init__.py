"""The stack's messages in Foxglove's schemas: one conversion (convert.py) used by the MCAP
export (slammtt-export --mcap) and the live WebSocket view (slammtt-foxglove, bridge.py)."""
