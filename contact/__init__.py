"""Analytic contact laws of a bearing outer ring in its support (foundation layer)."""
