"""Evaluation of the push-or-avoid scenarios: per-run metrics, the table, and the runner command."""
