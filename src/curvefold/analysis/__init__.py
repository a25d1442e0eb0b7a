"""Measurements, the geometric certificate and the check of FOLD files."""
