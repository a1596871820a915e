"""Physics models as plain functions and frozen parameter dataclasses (no Gymnasium)."""
